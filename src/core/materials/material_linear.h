// Corotated linear elasticity ("linear" in pair_coeff).

#ifndef PERISISSM_MATERIAL_LINEAR_H
#define PERISISSM_MATERIAL_LINEAR_H

#include "materials/material.h"

namespace PeriSISSM {

// W = mu * sum_k (s_k - 1)^2 + lambda/2 * (sum_k (s_k - 1))^2   (doc/pair_peri_nosb.rst).
// This is mu |F - R|^2 + lambda/2 tr(S - I)^2 with F = R S the polar decomposition taken
// through the signed SVD (R = U V^T, S = V diag(s) V^T). W is smooth in F except where an
// inverted F has |s_2| = |s_3| (the choice of which singular value is negative switches there;
// W is continuous but has a kink), as for every corotated model.
class LinearMaterial : public Material {
 public:
  static constexpr const char *kName = "linear";
  using Material::Material;
  const char *name() const override { return kName; }
  double energy(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d principal_stress(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d implicit_coefficient(const Eigen::Vector3d &s) const override;
  double plane_stress_stretch(double s1, double s2) const override;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_MATERIAL_LINEAR_H
