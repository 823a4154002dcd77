// The SISSM authors' membrane model with a C2 continuation below s_c.

#include "materials/material_xu.h"

#include <algorithm>

namespace PeriSISSM {

namespace {

  // h(s) = (s^-2 - 1)/2 and its first two derivatives at s_c: h' = -s^-3, h'' = 3 s^-4.
  constexpr double kInvSc = 1.0 / kXuThreshold;
  constexpr double kH0 = 0.5 * (kInvSc * kInvSc - 1.0);
  constexpr double kH1 = -kInvSc * kInvSc * kInvSc;
  constexpr double kH2 = 3.0 * kInvSc * kInvSc * kInvSc * kInvSc;

}    // namespace

// Above s_c, g(s) = (s^4 - 1)/4 + (s^-2 - 1)/2 = (s^6 - 3 s^2 + 2) / (4 s^2)
// = (s^2 - 1)^2 (s^2 + 2) / (4 s^2) = d^2 (s^2 + 2) / 4 with d = (s - 1)(s + 1)/s: a product of
// non-negative factors, accurate to round-off relative to g itself near s = 1 (where the
// defining form's two O(s - 1) terms cancel to O((s - 1)^2)). Below, the Taylor polynomial of h.
double XuMaterial::stretch_energy(double s)
{
  if (s >= kXuThreshold) {
    const double d = (s - 1.0) * (s + 1.0) / s;
    return 0.25 * d * d * (s * s + 2.0);
  }
  const double x = s - kXuThreshold;
  return 0.25 * (s * s * s * s - 1.0) + kH0 + kH1 * x + 0.5 * kH2 * x * x;
}

// Above s_c, s^3 - s^-3 = (s - 1/s)(s^2 + 1 + s^-2) = d (s^2 + 1 + s^-2), accurate near s = 1;
// below, s^3 + h'(s_c) + h''(s_c)(s - s_c).
double XuMaterial::stretch_slope(double s)
{
  if (s >= kXuThreshold) {
    const double d = (s - 1.0) * (s + 1.0) / s;
    return d * (s * s + 1.0 + 1.0 / (s * s));
  }
  return s * s * s + kH1 + kH2 * (s - kXuThreshold);
}

double XuMaterial::energy(const Eigen::Vector3d &s) const
{
  return mu_ / 3.0 * (stretch_energy(s(0)) + stretch_energy(s(1)) + stretch_energy(s(2)));
}

Eigen::Vector3d XuMaterial::principal_stress(const Eigen::Vector3d &s) const
{
  return mu_ / 3.0 * Eigen::Vector3d(stretch_slope(s(0)), stretch_slope(s(1)), stretch_slope(s(2)));
}

// c_k = s0 s_k^2 / 3 (header); clamped at 0 only for s0 < 0 (not a material).
Eigen::Vector3d XuMaterial::implicit_coefficient(const Eigen::Vector3d &s) const
{
  return std::max(mu_, 0.0) / 3.0 * s.cwiseProduct(s);
}

double XuMaterial::plane_stress_stretch(double /*s1*/, double /*s2*/) const
{
  return 1.0;
}

}    // namespace PeriSISSM
