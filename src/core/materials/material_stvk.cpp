// St. Venant-Kirchhoff.

#include "materials/material_stvk.h"

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

// E_k = (s_k^2 - 1)/2;  W = mu sum_k E_k^2 + lambda/2 (sum_k E_k)^2.
double StVKMaterial::energy(const Eigen::Vector3d &s) const
{
  const Eigen::Vector3d E = 0.5 * (s.cwiseProduct(s) - Eigen::Vector3d::Ones());
  const double trE = E.sum();
  return mu_ * E.squaredNorm() + 0.5 * lambda_ * trE * trE;
}

// dE_k/ds_k = s_k, so dW/ds_k = s_k (2 mu E_k + lambda trE).
Eigen::Vector3d StVKMaterial::principal_stress(const Eigen::Vector3d &s) const
{
  const Eigen::Vector3d E = 0.5 * (s.cwiseProduct(s) - Eigen::Vector3d::Ones());
  const double trE = E.sum();
  return s.cwiseProduct(2.0 * mu_ * E + Eigen::Vector3d::Constant(lambda_ * trE));
}

// Expanding Phat_k = s_k (2 mu E_k + lambda trE) by origin:
//   shear:       mu s_k^3                    - mu s_k
//   volumetric:  lambda/2 s_k sum_l s_l^2    - 3 lambda/2 s_k
// Implicit (a * s_k with a >= 0 at every state): mu s_k^2 * s_k (mu > 0), and, when
// lambda >= 0, lambda/2 (sum_l s_l^2) * s_k. So
//   c_k = mu s_k^2 + max(lambda, 0)/2 * sum_l s_l^2.
// Explicit: -(mu + 3 lambda/2) s_k = -(3K/2) s_k (always a softening term, like the "-4x" of the one-variable example),
// and, when lambda < 0, the whole volumetric term lambda s_k trE, whose slope in s_k,
// lambda (trE + s_k^2), has no fixed sign. Near F = I, c_k = mu + 3 max(lambda, 0)/2 while the
// tangent dPhat_k/ds_k = 2 mu + lambda.
Eigen::Vector3d StVKMaterial::implicit_coefficient(const Eigen::Vector3d &s) const
{
  const Eigen::Vector3d s2 = s.cwiseProduct(s);
  const double vol = 0.5 * std::max(lambda_, 0.0) * s2.sum();
  return std::max(mu_, 0.0) * s2 + Eigen::Vector3d::Constant(vol);
}

// Phat_3 = s3 (2 mu E3 + lambda trE) vanishes at s3 > 0 where 2 mu E3 + lambda (E1 + E2 + E3)
// = 0, i.e. E3 = -lambda (E1 + E2) / (2 mu + lambda): linear in s3^2 = 1 + 2 E3, whose root
// is unique. Written with Q = 1 + 2 E3, Phat_3 = (mu + lambda/2) s3 (s3^2 - Q), so when Q <= 0
// Phat_3 > 0 for every s3 > 0: W decreases all the way to s3 = 0, where its minimum over
// s3 >= 0 (W is even in s3: over all s3) lies, and 0 is returned. That is StVK's collapse
// under in-plane stretch: for lambda > 0 it occurs at s1^2 + s2^2 >= 3 + 2 mu / lambda (an
// equibiaxial stretch of 1.27 at nu = 0.45, 1.47 at nu = 0.3). E_k = (s_k - 1)(s_k + 1)/2 keeps
// round-off relative to the strain. Inadmissible 2 mu + lambda <= 0: the default solver.
double StVKMaterial::plane_stress_stretch(double s1, double s2) const
{
  const double p_wave = 2.0 * mu_ + lambda_;
  if (!(p_wave > 0.0)) return Material::plane_stress_stretch(s1, s2);
  const double e_sum = (s1 - 1.0) * (s1 + 1.0) + (s2 - 1.0) * (s2 + 1.0);    // 2 (E1 + E2)
  const double q = 1.0 - lambda_ * e_sum / p_wave;
  return q > 0.0 ? std::sqrt(q) : 0.0;
}

}    // namespace PeriSISSM
