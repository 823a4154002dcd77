// Fused multiply-add in the bond passes, on processors that have it.
//
// The bond passes (peri/elastic.cpp, peri/stabilization.cpp) are compiled twice: for plain
// x86-64, where madd<false>(a, b, c) is a * b + c, rounded twice, and for x86-64-v3 (AVX2 with
// FMA), where madd<true> is fma(a, b, c), rounded once. fused_passes() says which runs, the
// same on every process of a run (set_fused_passes). The compiler fuses nothing by itself
// (those files are compiled with -ffp-contract=off): whether it fuses a product can depend on
// the code around it, so the force of a step would depend on whether energy or virial was
// asked for in it, and a restarted run would no longer repeat the unsplit one bit for bit.
// With each fused operation written out, both versions are deterministic, sum in the same
// order on any number of ranks, and differ from each other in round-off only. The fused
// version also runs its bond loops 4-wide where the caller gives a columns scratch
// (ParticleFields::cols; linalg/double4.h): the same operations per component in the same
// order, the same bits.

#ifndef PERISISSM_LINALG_FUSED_H
#define PERISISSM_LINALG_FUSED_H

#include <cmath>

namespace PeriSISSM {

// a * b + c, in one rounding when FUSED
template <bool FUSED> [[gnu::always_inline]] inline double madd(double a, double b, double c)
{
  if constexpr (FUSED)
    return std::fma(a, b, c);
  else
    return a * b + c;
}

// True when the build has the x86-64-v3 code (-DPERISISSM_CPU_DISPATCH=ON, the default with GCC
// or Clang on x86-64) and the processor has AVX2 and FMA to run it.
bool x86_64_v3();

// True when this process could run the fused version: x86_64_v3() and the environment
// variable PERI_SISSM_PASSES is not "plain".
bool fused_passes_available();

// Chooses the version of the bond passes: fused when fused is true and x86_64_v3() (a process
// that cannot run the fused version runs the plain one whatever it is told). Processes that
// must agree bit for bit set the same choice: the glue sets the minimum of
// fused_passes_available() over its processes (pair peri/nosb's init_style).
void set_fused_passes(bool fused);

// True when the bond passes run their fused version: the choice of set_fused_passes(), or
// fused_passes_available() until one is made.
bool fused_passes();
// Which version fused_passes() runs, in words for the log.
const char *fused_passes_description();

}    // namespace PeriSISSM

// the target of the fused versions (with PERISISSM_CPU_DISPATCH)
#define PERISISSM_FUSED_TARGET __attribute__((target("arch=x86-64-v3")))

#endif    // PERISISSM_LINALG_FUSED_H
