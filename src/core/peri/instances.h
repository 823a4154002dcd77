// From run-time choices to compile-time instances of the bond passes (peri/elastic.cpp,
// peri/stabilization.cpp): the passes are templates on their flags (periodic box, virial,
// energy, membranes, breaking mode...) and on FUSED (linalg/fused.h); these helpers call a
// generic lambda with std::integral_constant arguments, so that one call site reaches every
// instance. Everything is inlined (always_inline, also on the lambdas: PERISISSM_INLINE), so
// that the instances of the fused version are compiled inside the one function that carries
// the x86-64-v3 target, and nowhere else.

#ifndef PERISISSM_PERI_INSTANCES_H
#define PERISISSM_PERI_INSTANCES_H

#include "linalg/fused.h"

#include <type_traits>

// for the lambdas given to the helpers below: inlined into their caller
#define PERISISSM_INLINE __attribute__((always_inline))

namespace PeriSISSM {

// f(I<a>) with I<v> = std::integral_constant<int, v>
template <class Fn> [[gnu::always_inline]] inline void with_flag(bool a, Fn &&f)
{
  if (a)
    f(std::integral_constant<int, 1>());
  else
    f(std::integral_constant<int, 0>());
}

// f(I<a>, I<b>)
template <class Fn> [[gnu::always_inline]] inline void with_flags(bool a, bool b, Fn &&f)
{
  with_flag(a, [&](auto ia) PERISISSM_INLINE {
    with_flag(b, [&](auto ib) PERISISSM_INLINE {
      f(ia, ib);
    });
  });
}

#ifdef PERISISSM_CPU_DISPATCH
// body(std::true_type()) in a function compiled for x86-64-v3
template <class Body> PERISISSM_FUSED_TARGET void with_fused(Body &body)
{
  body(std::true_type());
}
#endif

// body(std::true_type()) for the fused version where fused_passes() says so (compiled for
// x86-64-v3), body(std::false_type()) otherwise
template <class Body> [[gnu::always_inline]] inline void with_version(Body &&body)
{
#ifdef PERISISSM_CPU_DISPATCH
  if (fused_passes()) return with_fused(body);
#endif
  body(std::false_type());
}

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_INSTANCES_H
