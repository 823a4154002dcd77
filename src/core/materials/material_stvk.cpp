// St. Venant-Kirchhoff.

#include "materials/material_stvk.h"

#include <algorithm>

namespace PeriSISSM {

// E_k = (s_k^2 - 1)/2;  W = mu sum_k E_k^2 + lambda/2 (sum_k E_k)^2.
double StVKMaterial::energy(const Eigen::Vector3d& s) const
{
  const Eigen::Vector3d E = 0.5 * (s.cwiseProduct(s) - Eigen::Vector3d::Ones());
  const double trE = E.sum();
  return mu_ * E.squaredNorm() + 0.5 * lambda_ * trE * trE;
}

// dE_k/ds_k = s_k, so dW/ds_k = s_k (2 mu E_k + lambda trE).
Eigen::Vector3d StVKMaterial::principal_stress(const Eigen::Vector3d& s) const
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
Eigen::Vector3d StVKMaterial::implicit_coefficient(const Eigen::Vector3d& s) const
{
  const Eigen::Vector3d s2 = s.cwiseProduct(s);
  const double vol = 0.5 * std::max(lambda_, 0.0) * s2.sum();
  return std::max(mu_, 0.0) * s2 + Eigen::Vector3d::Constant(vol);
}

}  // namespace PeriSISSM
