// Four doubles in one register, for the fused version of the bond passes (linalg/fused.h): one
// 4-wide AVX register (__m256d, which GCC and Clang also treat as a vector of four doubles for
// + - *) in the x86-64-v3 code those passes are compiled to. Each lane does what the scalar
// code does to one component, operation for operation (a fused multiply-add is one per lane,
// rounded once), so a pass written with these gives the same bits as the scalar fused version
// of the same sums. A 3-vector takes lanes 0-2; what lane 3 holds is said where it is used.
//
// Loads are chosen so that a bond needs no shuffles (the one shuffle port is what 4-wide code
// waits on): a number that multiplies a whole vector comes as a broadcast from memory, a
// 3-vector as a masked load; values leave the registers through stores, never by lane. The
// exception is the breaking check (peri/elastic.cpp), where seven shuffles (columns3) turn four
// bonds' rows into columns in place of some twenty scalar operations per bond.
//
// Only in builds with PERISISSM_CPU_DISPATCH; compiled for x86-64-v3 (PERISISSM_FUSED_TARGET),
// so only functions with that target may call them.

#ifndef PERISISSM_LINALG_DOUBLE4_H
#define PERISISSM_LINALG_DOUBLE4_H

#ifdef PERISISSM_CPU_DISPATCH

#include "linalg/fused.h"

#include <immintrin.h>

namespace PeriSISSM {

typedef __m256d Double4;

// a[0..3]
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 load4(const double *a)
{
  return _mm256_loadu_pd(a);
}

// a[0..2] and 0 (reads three doubles only)
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 load3(const double *a)
{
  return _mm256_maskload_pd(a, _mm256_set_epi64x(0, -1, -1, -1));
}

// *a in every lane
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 bcast(const double *a)
{
  return _mm256_broadcast_sd(a);
}

// a in every lane
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 splat(double a)
{
  return _mm256_set1_pd(a);
}

// v into a[0..3]
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void store4(double *a, Double4 v)
{
  _mm256_storeu_pd(a, v);
}

// lane 0
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline double lane0(Double4 v)
{
  return _mm256_cvtsd_f64(v);
}

// a * b + c per lane, rounded once
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 fma4(Double4 a, Double4 b, Double4 c)
{
  return _mm256_fmadd_pd(a, b, c);
}

// c + w a per lane (a: four doubles in memory), rounded once
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 fma4(double w, const double *a,
                                                                  Double4 c)
{
  return fma4(splat(w), load4(a), c);
}

// a[j0], a[j1], a[j2], a[j3] (four loads and the shuffles that join them)
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 load_at(const double *a, int j0,
                                                                     int j1, int j2, int j3)
{
  return _mm256_set_pd(a[j3], a[j2], a[j1], a[j0]);
}

// std::max(a, b) per lane: b where a < b, else a (also where either is NaN)
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 max4(Double4 a, Double4 b)
{
  return _mm256_max_pd(b, a);
}

// masks: all bits of a lane set where a < b (a > b), clear where not or where either is NaN
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 less4(Double4 a, Double4 b)
{
  return _mm256_cmp_pd(a, b, _CMP_LT_OQ);
}
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 greater4(Double4 a, Double4 b)
{
  return _mm256_cmp_pd(a, b, _CMP_GT_OQ);
}

// the lanes set in a or b
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 or4(Double4 a, Double4 b)
{
  return _mm256_or_pd(a, b);
}

// whether any lane of a mask is set
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline bool any4(Double4 mask)
{
  return _mm256_movemask_pd(mask) != 0;
}

// (a0, b1, c2, d3): lane l of the l-th argument (three blends)
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 lanes(Double4 a, Double4 b, Double4 c,
                                                                   Double4 d)
{
  return _mm256_blend_pd(_mm256_blend_pd(a, b, 0x2), _mm256_blend_pd(c, d, 0x8), 0xC);
}

// lanes 0-2 of the rows a, b, c, d as columns: c0 = (a0, b0, c0, d0), c1 = (a1, b1, c1, d1),
// c2 = (a2, b2, c2, d2); seven shuffles, for code that does one thing to four 3-vectors' like
// components at once
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void
columns3(Double4 a, Double4 b, Double4 c, Double4 d, Double4 &c0, Double4 &c1, Double4 &c2)
{
  const Double4 ab02 = _mm256_unpacklo_pd(a, b), ab13 = _mm256_unpackhi_pd(a, b);
  const Double4 cd02 = _mm256_unpacklo_pd(c, d), cd13 = _mm256_unpackhi_pd(c, d);
  c0 = _mm256_permute2f128_pd(ab02, cd02, 0x20);
  c1 = _mm256_permute2f128_pd(ab13, cd13, 0x20);
  c2 = _mm256_permute2f128_pd(ab02, cd02, 0x31);
}

// M x with M given by its columns c0, c1, c2 (lanes 0-2: rows) and x by its components, each
// in every lane of x0, x1, x2; summed as the scalar passes sum each row:
// fma(M_r2, x_2, fma(M_r1, x_1, M_r0 * x_0))
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4
mat_vec(Double4 c0, Double4 c1, Double4 c2, Double4 x0, Double4 x1, Double4 x2)
{
  return fma4(c2, x2, fma4(c1, x1, c0 * x0));
}

}    // namespace PeriSISSM

#endif    // PERISISSM_CPU_DISPATCH

#endif    // PERISISSM_LINALG_DOUBLE4_H
