// Compressible neo-Hookean with a C2 continuation below J0.

#include "materials/material_neohookean.h"

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

namespace {

  // psi(x) = x - ln(1 + x) >= 0 for x > -1, accurate to round-off relative to psi itself.
  // Written as x - log1p(x) it loses ~2 eps / |x| relative near 0, where psi ~ x^2/2. With
  // u = x / (2 + x), ln(1 + x) = 2 atanh(u) = 2 (u + u^3/3 + u^5/5 + ...) and x - 2u = x u, so
  //   psi(x) = x u - 2 (u^3/3 + u^5/5 + ...),
  // a leading term free of cancellation plus a series that is smaller by ~|x|/6 and converges
  // like u^2. Used for |x| <= 1/4 (|u| <= 1/7: 20 terms reach u^41 < 1e-34, below round-off of
  // psi >= x^2/3 there); beyond, x - log1p(x) loses at most a factor |x|/psi(x) < 10.
  double x_minus_log1p(double x)
  {
    if (!(std::abs(x) <= 0.25)) return x - std::log1p(x);
    const double u = x / (2.0 + x);
    const double u2 = u * u;
    double term = u * u2, series = 0.0;
    for (int k = 3; k <= 41; k += 2) {
      series += term / k;
      term *= u2;
    }
    return x * u - 2.0 * series;
  }

}    // namespace

// W = mu/2 (|s|^2 - 3) + g(J), J = s_1 s_2 s_3, evaluated so that W near rest (where W ~ e^2
// for F = I + O(e) but its terms are O(e) each) keeps round-off accuracy relative to W itself.
// With e_k = s_k - 1 (exact in floating point near 1), when every s_k > 0 and J >= J0:
//   mu/2 (s_k^2 - 1) - mu ln s_k = mu (e_k^2/2 + e_k - log1p(e_k)) = mu (e_k^2/2 + psi(e_k)),
//   ln J = sum_k log1p(e_k),
// so W = mu sum_k (e_k^2/2 + psi(e_k)) + lambda/2 (ln J)^2: the mu part is a sum of
// non-negative terms, and nothing cancels. Equal to the defining form in exact arithmetic.
// Otherwise (J < J0: continued volumetric term, or a non-positive s_k, which the signed SVD
// gives only for J <= 0) W = mu/2 sum_k (s_k - 1)(s_k + 1) + g(J), far from rest.
double NeoHookeanMaterial::energy(const Eigen::Vector3d &s) const
{
  const double J = s.prod();
  if (J >= j0_ && s.minCoeff() > 0.0) {
    double shear = 0.0, lnj = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double e = s(k) - 1.0;
      shear += 0.5 * e * e + x_minus_log1p(e);
      lnj += std::log1p(e);
    }
    return mu_ * shear + 0.5 * lambda_ * lnj * lnj;
  }
  double shear = 0.0;
  for (int k = 0; k < 3; ++k) shear += (s(k) - 1.0) * (s(k) + 1.0);
  return 0.5 * mu_ * shear + volumetric_energy(J);
}

// dJ/ds_k = J/s_k = product of the other two singular values (no division: finite at s_k = 0),
// so Phat_k = mu s_k + g'(J) s_l s_m.
Eigen::Vector3d NeoHookeanMaterial::principal_stress(const Eigen::Vector3d &s) const
{
  const double dg = volumetric_slope(s.prod());
  const Eigen::Vector3d cof(s(1) * s(2), s(0) * s(2), s(0) * s(1));
  return mu_ * s + dg * cof;
}

// g''(J) = (mu + lambda (1 - ln J)) / J^2 above J0; the constant g''(J0) below.
double NeoHookeanMaterial::volumetric_curvature(double J) const
{
  if (J >= j0_) return (mu_ + lambda_ * (1.0 - std::log(J))) / (J * J);
  return g2_;
}

// Phat_k = mu s_k + g'(J) s_l s_m. Its slope in s_k is mu + g''(J) (s_l s_m)^2 (s_l s_m does
// not depend on s_k). Both parts grow with s_k where g'' > 0, so c_k holds the whole tangent
// there: c_k = mu + max(g''(J), 0) (s_l s_m)^2 >= 0, which at rest is the P-wave modulus
// 2 mu + lambda, as for the linear model (with c_k = mu alone the SISSM block missed the
// volumetric stiffness and the iteration diverged beyond twice the explicit time step).
// The rest, g'(J) s_l s_m - max(g'', 0) (s_l s_m)^2 s_k, is explicit.
Eigen::Vector3d NeoHookeanMaterial::implicit_coefficient(const Eigen::Vector3d &s) const
{
  const double curv = std::max(volumetric_curvature(s.prod()), 0.0);
  const Eigen::Vector3d cof(s(1) * s(2), s(0) * s(2), s(0) * s(1));
  return Eigen::Vector3d::Constant(std::max(mu_, 0.0)) + curv * cof.cwiseProduct(cof);
}

// Newton on phi(t) = Phat_3(s1, s2, e^t) = mu s3 + g'(J) s1 s2 (principal_stress itself, so the
// continuation below J0 is included) with the analytic slope
// dphi/dt = s3 dPhat_3/ds3 = s3 (mu + g''(J) (s1 s2)^2), g'' the continued curvature (constant
// g''(J0) below J0). g'' >= 0 everywhere (header), so for mu > 0 phi increases with s3 and its
// root is unique; it always exists for s1, s2 > 0: phi -> s1 s2 g'(0) < 0 as s3 -> 0 and
// phi ~ mu s3 for large s3.
double NeoHookeanMaterial::plane_stress_stretch(double s1, double s2) const
{
  const double a = s1 * s2;
  return plane_stress_newton([this, s1, s2, a](double t) {
    const double s3 = std::exp(t);
    const double phi = principal_stress(Eigen::Vector3d(s1, s2, s3))(2);
    return PlaneStressSample{phi, s3 * (mu_ + volumetric_curvature(a * s3) * a * a)};
  });
}

}    // namespace PeriSISSM
