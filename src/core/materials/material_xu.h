// The membrane model of the SISSM authors (Xu et al.), "xu" in pair_coeff, with a C2
// continuation to strong compression and inversion.

#ifndef PERISISSM_MATERIAL_XU_H
#define PERISISSM_MATERIAL_XU_H

#include "materials/material.h"

namespace PeriSISSM {

// Continuation threshold s_c of the xu model: the lower clamp of the authors' membrane code.
constexpr double kXuThreshold = 0.3;

// W = s0/3 sum_k g(s_k), one parameter s0 (stress units), with
//   g(s) = (s^4 - 1)/4 + h(s),
//   h(s) = (s^-2 - 1)/2                                          for s >= s_c,
//   h(s) = h(s_c) + h'(s_c) (s - s_c) + h''(s_c)/2 (s - s_c)^2   for s <  s_c,
// so that Phat_k = s0/3 g'(s_k) = s0/3 (s_k^3 - s_k^-3) for s_k >= s_c: the authors' principal
// stresses (doc/pair_peri_nosb.rst). For s >= s_c, g(s) = (s^2 - 1)^2 (s^2 + 2) / (4 s^2) >= 0.
//
// Small strain: dPhat_k/ds_k = s0/3 g''(1) = 2 s0 and the k do not couple, so the model is
// linear elasticity with mu = s0, lambda = 0: E = 2 s0, nu = 0 (K = 2 s0/3, G = s0). It is
// built on the base class as Material(mu = s0, lambda = 0).
//
// Continuation. Only the singular term h, the energy of s^-2, needs one: below s_c it is its
// second-order Taylor polynomial about s_c (s^4 is smooth everywhere), so g, W and Phat are C2
// across s_c and finite for every finite s, s_k = 0 and s_k < 0 (inverted) included. It is not
// the even extension g(|s|): g is even above 0, but an even continuation would make the
// inverted s = -1 a second stress-free state and push s in (-1, 0) further into inversion.
// With the Taylor polynomial g keeps penalizing compression: g''(s) = 3 s^2 + h'' > 0 for all s
// (g is strictly convex, its minimum g = 0 is s = 1 alone), and for s < s_c,
// g'(s) = s^3 + h'(s_c) + h''(s_c)(s - s_c) <= s_c^3 - s_c^-3 < 0, so the restoring force
// points to s = 1 at every compressed or inverted state. Since g is not even, W has a kink
// where an inverted F has |s_2| = |s_3| (the choice of the negative singular value switches),
// like the corotated models (material_linear.h).
//
// Implicit coefficients (the rule of material.h): Phat_k = s0/3 s_k^3 + s0/3 h'(s_k). The
// first term is (s0 s_k^2 / 3) s_k with a non-negative factor at every state: implicit,
// c_k = s0 s_k^2 / 3 (continuous in s). The second is -s0/3 s_k^-3 above s_c and its linear
// continuation below; as one term over all states it is not of the form a s_k with a >= 0, so
// it stays explicit everywhere (the authors' split, -s^-3 explicit). Near rest c_k = s0/3,
// a sixth of the tangent 2 s0.
class XuMaterial : public Material {
 public:
  static constexpr const char *kName = "xu";

  // Inputs: s0 the model's stress parameter (stress units); mu() = s0, lambda() = 0.
  explicit XuMaterial(double s0) : Material(s0, 0.0) {}

  const char *name() const override { return kName; }
  double energy(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d principal_stress(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d implicit_coefficient(const Eigen::Vector3d &s) const override;

  // Plane stress: Phat_3 = s0/3 g'(s3) does not depend on s1, s2 and vanishes only at s3 = 1.
  // Inputs: s1, s2 (unused). Outputs: 1.
  double plane_stress_stretch(double s1, double s2) const override;

  double s0() const { return mu_; }

  // The one-variable energy g(s) (continued below kXuThreshold), dimensionless.
  // Inputs: s any finite signed singular value. Outputs: g(s) >= 0, g(1) = 0.
  static double stretch_energy(double s);

  // Its slope g'(s) = s^3 - s^-3 (continued below kXuThreshold).
  // Inputs: s any finite value. Outputs: g'(s) (< 0 for s < 1, > 0 for s > 1).
  static double stretch_slope(double s);
};

}    // namespace PeriSISSM

#endif    // PERISISSM_MATERIAL_XU_H
