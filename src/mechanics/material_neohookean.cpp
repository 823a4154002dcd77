// Compressible neo-Hookean with a C2 continuation below J0.

#include "material_neohookean.h"

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

// J0 = 0.1, raised for lambda < 0 to J* = exp(1 + mu/lambda) where g''(J*) = 0 (header).
// Capped below 1 so that ln J0 < 0; g2 is clamped at 0, which only matters for inadmissible
// parameters (K <= 0), where C2 is then traded for a non-negative curvature.
NeoHookeanMaterial::NeoHookeanMaterial(double mu, double lambda) : Material(mu, lambda)
{
  j0_ = kNeoHookeanJ0;
  if (lambda_ < 0.0 && mu_ > 0.0) j0_ = std::max(j0_, std::exp(1.0 + mu_ / lambda_));
  j0_ = std::min(j0_, 0.9);
  const double lnj0 = std::log(j0_);
  g0_ = -mu_ * lnj0 + 0.5 * lambda_ * lnj0 * lnj0;
  g1_ = (lambda_ * lnj0 - mu_) / j0_;
  g2_ = std::max((mu_ + lambda_ * (1.0 - lnj0)) / (j0_ * j0_), 0.0);
}

// g(J) = -mu ln J + lambda/2 (ln J)^2 above J0; Taylor polynomial about J0 below.
double NeoHookeanMaterial::volumetric_energy(double J) const
{
  if (J >= j0_) {
    const double lnj = std::log(J);
    return -mu_ * lnj + 0.5 * lambda_ * lnj * lnj;
  }
  const double d = J - j0_;
  return g0_ + g1_ * d + 0.5 * g2_ * d * d;
}

// g'(J) = (lambda ln J - mu) / J above J0; g'(J0) + g''(J0) (J - J0) below.
double NeoHookeanMaterial::volumetric_slope(double J) const
{
  if (J >= j0_) return (lambda_ * std::log(J) - mu_) / J;
  return g1_ + g2_ * (J - j0_);
}

// W = mu/2 (|s|^2 - 3) + g(s_1 s_2 s_3).
double NeoHookeanMaterial::energy(const Eigen::Vector3d& s) const
{
  return 0.5 * mu_ * (s.squaredNorm() - 3.0) + volumetric_energy(s.prod());
}

// dJ/ds_k = J/s_k = product of the other two singular values (no division: finite at s_k = 0),
// so Phat_k = mu s_k + g'(J) s_l s_m.
Eigen::Vector3d NeoHookeanMaterial::principal_stress(const Eigen::Vector3d& s) const
{
  const double dg = volumetric_slope(s.prod());
  const Eigen::Vector3d cof(s(1) * s(2), s(0) * s(2), s(0) * s(1));
  return mu_ * s + dg * cof;
}

// Phat_k = mu s_k (shear, implicit: c_k = mu) + g'(J) J/s_k (volumetric: its sign and slope
// depend on J and on the other two singular values, explicit).
Eigen::Vector3d NeoHookeanMaterial::implicit_coefficient(const Eigen::Vector3d& /*s*/) const
{
  return Eigen::Vector3d::Constant(std::max(mu_, 0.0));
}

}  // namespace PeriSISSM
