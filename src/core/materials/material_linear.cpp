// Corotated linear elasticity.

#include "materials/material_linear.h"

#include <algorithm>

namespace PeriSISSM {

// W = mu |s - 1|^2 + lambda/2 (tr)^2 with tr = sum_k (s_k - 1).
double LinearMaterial::energy(const Eigen::Vector3d& s) const
{
  const Eigen::Vector3d e = s - Eigen::Vector3d::Ones();
  const double tr = e.sum();
  return mu_ * e.squaredNorm() + 0.5 * lambda_ * tr * tr;
}

// dW/ds_k = 2 mu (s_k - 1) + lambda tr.
Eigen::Vector3d LinearMaterial::principal_stress(const Eigen::Vector3d& s) const
{
  const Eigen::Vector3d e = s - Eigen::Vector3d::Ones();
  return 2.0 * mu_ * e + Eigen::Vector3d::Constant(lambda_ * e.sum());
}

// Phat_k = (2 mu + lambda) s_k + [lambda sum_{l != k} s_l - 2 mu - 3 lambda]. Phat_k is linear
// in s_k; its collected coefficient is the P-wave modulus 2 mu + lambda = K + 4G/3, which is
// dPhat_k/ds_k exactly and > 0 for every admissible material (also for lambda < 0, nu < 0).
// So c_k = 2 mu + lambda, the same for all k (H_i is isotropic, doc/theory.rst); the
// bracket is explicit. Clamped at 0 only for inadmissible parameters (K + 4G/3 <= 0).
Eigen::Vector3d LinearMaterial::implicit_coefficient(const Eigen::Vector3d& /*s*/) const
{
  return Eigen::Vector3d::Constant(std::max(2.0 * mu_ + lambda_, 0.0));
}

}  // namespace PeriSISSM
