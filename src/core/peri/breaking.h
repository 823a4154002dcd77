// The bond-breaking rule and the critical stretch from a fracture energy (doc/theory.rst,
// "Bond breaking").
//
// The critical stretch of bond ij is the one its type pair gives:
//   s0_ij = s00_IJ - alpha_IJ max(s_min,i, s_min,j)
// where s_min,i is the smallest stretch among the unbroken bonds of i at the previous
// evaluation. For a single pair of s00 and alpha this is the rule of peri/lps,
// min(s0_i, s0_j) with s0_i = s00 - alpha s_min,i. A bond breaks when its stretch
// (|eta| - |xi|)/|xi| exceeds s0_ij; both ends see the same stretch and the same s_min values,
// so both families lose the bond in the same evaluation.

#ifndef PERISISSM_PERI_BREAKING_H
#define PERISISSM_PERI_BREAKING_H

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

namespace PeriSISSM {

class BreakingRule {
 public:
  enum Mode { NOBREAK = 0, S0ONLY, BREAK };    // no check; s_min only; break and s_min

  // Inputs: ntypes; for every type pair 1 <= i, j <= ntypes (symmetric) whether its bonds
  // break, s00 and alpha (given by the callables brk(i, j), s00(i, j), alpha(i, j)).
  template <class B, class S, class A> void configure(int ntypes, B brk, S s00, A alpha)
  {
    n_ = ntypes + 1;
    break_.assign(n_ * n_, 0);
    s00_.assign(n_ * n_, 0.0);
    alpha_.assign(n_ * n_, 0.0);
    any_ = false;
    uniform_ = true;
    for (int i = 1; i < n_; i++)
      for (int j = 1; j < n_; j++) {
        break_[i * n_ + j] = brk(i, j) ? 1 : 0;
        s00_[i * n_ + j] = s00(i, j);
        alpha_[i * n_ + j] = alpha(i, j);
        if (brk(i, j)) any_ = true;
        if (!brk(i, j) || s00(i, j) != s00(1, 1) || alpha(i, j) != alpha(1, 1)) uniform_ = false;
      }
    if (n_ > 1) {
      s00u_ = s00(1, 1);
      alphau_ = alpha(1, 1);
    }
  }

  bool any() const { return any_; }
  // every type pair breakable with the same s00 and alpha
  bool uniform() const { return uniform_; }

  // One bond check (MODE = BREAK: break and update s_min; S0ONLY: s_min only).
  // r2 = |eta|^2, q2 = |xi|^2, smax = max(s_min,i, s_min,j). UNIFORM: compared as
  // r2 > (1 + s0_ij)^2 q2, and the smallest r2/q2 kept as the fraction acc/den, so that s_min
  // costs no division or sqrt per bond. Otherwise acc is the smallest stretch. Returns true if
  // the bond breaks.
  template <int MODE, int UNIFORM>
  inline bool check(double r2, double q2, int itype, int jtype, double smax, double &acc,
                    double &den) const
  {
    if (UNIFORM) {
      if (MODE == BREAK) {
        const double lim = 1.0 + s00u_ - alphau_ * smax;
        if (lim < 0.0 || r2 > lim * lim * q2) return true;
      }
      keep_smaller(r2, q2, acc, den);
    } else {
      const double stretch = sqrt(r2 / q2) - 1.0;
      const int ij = itype * n_ + jtype;
      if (MODE == BREAK && break_[ij] && stretch > s00_[ij] - alpha_[ij] * smax) return true;
      acc = std::min(acc, stretch);
      den = 1.0;
    }
    return false;
  }

  // the s00 and alpha of every pair when uniform()
  double uniform_s00() const { return s00u_; }
  double uniform_alpha() const { return alphau_; }

  // The UNIFORM check's smallest r2/q2, kept as the fraction acc/den: r2, q2 replace it if
  // smaller.
  static inline void keep_smaller(double r2, double q2, double &acc, double &den)
  {
    if (r2 * den < acc * q2) {
      acc = r2;
      den = q2;
      // kept a branch, not a conditional move: a family's smallest stretch changes a few
      // times (about ln n of its n bonds in random order), and conditional moves would chain
      // every bond's comparison to the one before (an empty asm statement is not
      // if-converted; in a 54K lattice this took s_min from ~15 % of the state pass to ~7 %)
#if defined(__GNUC__)
      asm volatile("");
#endif
    }
  }

  // start value of acc for check()
  template <int UNIFORM> static constexpr double initial()
  {
    return UNIFORM ? 1.0 : DBL_MAX;
  }

  // s_min from the accumulated checks; sold if there was no unbroken bond
  template <int UNIFORM> static inline double smin_from(double acc, double den, double sold)
  {
    if (den == 0.0) return sold;
    if (UNIFORM) return sqrt(acc / den) - 1.0;
    return acc;
  }

 private:
  int n_ = 0;
  bool any_ = false, uniform_ = false;
  double s00u_ = 0.0, alphau_ = 0.0;
  std::vector<int> break_;
  std::vector<double> s00_, alpha_;
};

// Critical stretch from the fracture energy G0 (pair_coeff keyword G0):
//   G0 = delta s00^2 (kG0CoefM (K + 4G/3) + kG0CoefS Cs K delta / h)
// measured with the rigid-halves separation test (examples/fracture-energy/run.py) on a simple
// cubic lattice with delta = 3.0002 h, alpha = 0, model linear, small-strain limit (s00 = 1e-6;
// at finite s00 the measured G0 is lower by about 4.5 s00 relative): the dissipated work per
// area is exactly linear in K + 4G/3 (the particles at the crack are in uniaxial strain) and in
// Cs K (stabilization); the stabilization part grows about like delta/h (measured
// 2.5 <= delta/h <= 6), hence the factor delta/h.
// Inputs: G0 (energy / area), K, G (stress), Cs, delta horizon and h particle spacing (length).
// Outputs: s00 (dimensionless).
// With the length form of the stabilization (deviation length) its share does not grow with
// delta/h:
//   G0 = delta s00^2 (kG0CoefM (K + 4G/3) + kG0CoefL Cs K)
// measured with the same test at delta = 3.0002 h, s00 = 1e-6: 1.00391 Cs K for Cs = 1 and 2
// and Poisson's ratio 0 and 0.25 (residuals below 1e-5); at delta/h = 2.5, 4.0002 and 5.0002 the
// stabilization's share is 0.97 to 1.04 of this (examples/fracture-energy/README.md).
constexpr double kG0CoefM = 0.58376;
constexpr double kG0CoefS = 1.19321;
constexpr double kG0CoefL = 1.00391;
double s00_from_fracture_energy(double g0, double k, double g, double cs, double delta, double h,
                                bool length);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_BREAKING_H
