// St. Venant-Kirchhoff ("stvk" in pair_coeff).

#ifndef PERISISSM_MATERIAL_STVK_H
#define PERISISSM_MATERIAL_STVK_H

#include "materials/material.h"

namespace PeriSISSM {

// W = mu E:E + lambda/2 tr(E)^2, E = (F^T F - I)/2   (doc/pair_peri_nosb.rst).
// With F = U diag(s) V^T, E = V diag(E_k) V^T, E_k = (s_k^2 - 1)/2, so
// W = mu sum_k E_k^2 + lambda/2 (sum_k E_k)^2: a polynomial in F, smooth everywhere.
// Known property of the model (not of this code): it softens in strong compression, F = 0 is
// an equilibrium and a fully inverted F = -R has W = 0, so it is not inversion-safe.
class StVKMaterial : public Material {
 public:
  static constexpr const char *kName = "stvk";
  using Material::Material;
  const char *name() const override { return kName; }
  double energy(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d principal_stress(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d implicit_coefficient(const Eigen::Vector3d &s) const override;
  double plane_stress_stretch(double s1, double s2) const override;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_MATERIAL_STVK_H
