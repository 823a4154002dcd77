// Corotated linear elasticity.

#include "materials/material_linear.h"

#include <algorithm>

namespace PeriSISSM {

// W = mu |s - 1|^2 + lambda/2 (tr)^2 with tr = sum_k (s_k - 1).
double LinearMaterial::energy(const Eigen::Vector3d &s) const
{
  const Eigen::Vector3d e = s - Eigen::Vector3d::Ones();
  const double tr = e.sum();
  return mu_ * e.squaredNorm() + 0.5 * lambda_ * tr * tr;
}

// dW/ds_k = 2 mu (s_k - 1) + lambda tr.
Eigen::Vector3d LinearMaterial::principal_stress(const Eigen::Vector3d &s) const
{
  const Eigen::Vector3d e = s - Eigen::Vector3d::Ones();
  return 2.0 * mu_ * e + Eigen::Vector3d::Constant(lambda_ * e.sum());
}

// Phat_k = (2 mu + lambda) s_k + [lambda sum_{l != k} s_l - 2 mu - 3 lambda]. Phat_k is linear
// in s_k; its collected coefficient is the P-wave modulus 2 mu + lambda = K + 4G/3, which is
// dPhat_k/ds_k exactly and > 0 for every admissible material (also for lambda < 0, nu < 0).
// So c_k = 2 mu + lambda, the same for all k (H_i is isotropic, doc/theory.rst); the
// bracket is explicit. Clamped at 0 only for inadmissible parameters (K + 4G/3 <= 0).
Eigen::Vector3d LinearMaterial::implicit_coefficient(const Eigen::Vector3d & /*s*/) const
{
  return Eigen::Vector3d::Constant(std::max(2.0 * mu_ + lambda_, 0.0));
}

// Phat_3 = 2 mu e3 + lambda (e1 + e2 + e3) is linear in s3 with slope 2 mu + lambda > 0, so
// its one root is e3 = -lambda (e1 + e2) / (2 mu + lambda). When 1 + e3 <= 0, W is increasing
// on s3 > 0 (its minimum lies at s3 <= 0, an inverted thickness) and 0 is returned, the
// minimizer over s3 >= 0: for lambda > 0 this is s1 + s2 >= 3 + 2 mu / lambda (an equibiaxial
// stretch of 1.61 at nu = 0.45, 2.17 at nu = 0.3). Inadmissible 2 mu + lambda <= 0: the
// default solver.
double LinearMaterial::plane_stress_stretch(double s1, double s2) const
{
  const double p_wave = 2.0 * mu_ + lambda_;
  if (!(p_wave > 0.0)) return Material::plane_stress_stretch(s1, s2);
  const double s3 = 1.0 - lambda_ * ((s1 - 1.0) + (s2 - 1.0)) / p_wave;
  return s3 > 0.0 ? s3 : 0.0;
}

}    // namespace PeriSISSM
