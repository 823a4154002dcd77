// Compressible neo-Hookean with a smooth continuation to collapsed and inverted states
// ("neohookean" in pair_coeff).

#ifndef PERISISSM_MATERIAL_NEOHOOKEAN_H
#define PERISISSM_MATERIAL_NEOHOOKEAN_H

#include "materials/material.h"

namespace PeriSISSM {

// Default continuation threshold J0 of the neo-Hookean volumetric term (see below).
constexpr double kNeoHookeanJ0 = 0.1;

// W = mu/2 (sum_k s_k^2 - 3) + g(J),  J = s_1 s_2 s_3 = det F,
//   g(J) = -mu ln J + lambda/2 (ln J)^2                               for J >= J0,
//   g(J) = g(J0) + g'(J0) (J - J0) + g''(J0)/2 (J - J0)^2             for J <  J0,
// i.e. below J0 the volumetric term is its second-order Taylor polynomial about J0: W is C2
// across J = J0, finite with finite P for every F (J <= 0 included).
//
// Threshold and restoring property. g'(J) = (lambda ln J - mu)/J and
// g''(J) = (mu + lambda (1 - ln J))/J^2. For J < J0 the continued slope is
// g'(J0) + g''(J0)(J - J0) <= g'(J0) < 0 (pushes J up) whenever g''(J0) >= 0 and g'(J0) < 0:
//  - lambda >= 0: both hold for any J0 < 1; J0 = kNeoHookeanJ0 = 0.1.
//  - lambda < 0 (nu < 0): g'' changes sign at J* = exp(1 + mu/lambda); J0 = max(0.1, J*), so
//    g''(J0) >= 0 (= 0 when J0 = J*: the continuation is then linear, with g' at its most
//    negative value), and g'(J0) < 0 because |ln J0| <= mu/|lambda| - 1. K > 0 gives
//    |lambda| < 2mu/3, so J* < exp(-1/2) ~ 0.61.
// Limits that no continuation of g alone can remove (the restoring ranges stated are tested):
//  - F = 0 is an equilibrium of every isotropic C1 energy (P(0) = R P(0) for all rotations R
//    forces P(0) = 0), and here a strict local minimum: near F = 0, W ~ mu/2 |F|^2 + g(0) +
//    g'(0) det F, and det F is cubic. Along uniform compression F = t I, dW/dJ = mu/t + g'(J)
//    is negative (restoring) only for J = t^3 above the root J_c of mu J^(-1/3) = -g'(J).
//    For lambda >= 0 and J0 = 0.1: above J0, J dW/dJ = mu (J^(2/3) - 1) + lambda ln J < 0 up
//    to J = 1; below J0, mu J^(-1/3) + g'(J) is convex in J, negative at J0, and g' <= g'(J0),
//    so it is restoring on (J_c, 1) with J_c <= (mu/|g'(J0)|)^3 <= J0^3 = 1e-3. Measured:
//    J_c = 1.25e-4 (lambda = 0, ~(mu/|g'(0)|)^3 with g'(0) = -(20 mu + 56 lambda)),
//    8.9e-7 (nu = 0.3), 4.7e-11 (nu = 0.49).
//    Uniaxial collapse and inversion, F = diag(1, 1, t) with t in (-inf, J0), are restoring.
//  - With lambda < 0 the model itself stops being restoring under strong uniform compression,
//    because g' grows back towards 0 and the mu |F|^2 term wins: for nu = -0.3 the original
//    energy is restoring only for J > 0.145; with the continuation (J0 = 0.189, linear in J)
//    for J > 0.128. Only the volumetric term g is guaranteed restoring for every J < J0.
class NeoHookeanMaterial : public Material {
 public:
  static constexpr const char *kName = "neohookean";

  // Inputs: mu, lambda Lame constants. Computes J0 and the Taylor coefficients.
  NeoHookeanMaterial(double mu, double lambda);

  const char *name() const override { return kName; }
  double energy(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d principal_stress(const Eigen::Vector3d &s) const override;
  Eigen::Vector3d implicit_coefficient(const Eigen::Vector3d &s) const override;
  double plane_stress_stretch(double s1, double s2) const override;

  // Continuation threshold J0 (dimensionless, in [0.1, 1)).
  double continuation_threshold() const { return j0_; }

  // Volumetric energy g(J) (continued below J0).
  // Inputs: J = det F, any real. Outputs: g (stress units).
  double volumetric_energy(double J) const;

  // Its slope g'(J) (continued below J0).
  // Inputs: J = det F, any real. Outputs: dg/dJ (stress units).
  double volumetric_slope(double J) const;
  // g''(J), the volumetric curvature (the constant g''(J0) below J0).
  double volumetric_curvature(double J) const;

 private:
  double j0_;    // continuation threshold
  double g0_;    // g(J0)
  double g1_;    // g'(J0)
  double g2_;    // g''(J0) (>= 0)
};

}    // namespace PeriSISSM

#endif    // PERISISSM_MATERIAL_NEOHOOKEAN_H
