// First Piola-Kirchhoff stress from the signed SVD, and the per-particle quantities of the
// peridynamic kernels (math.md sections 1-2).

#ifndef PERISISSM_STRESS_H
#define PERISISSM_STRESS_H

#include "material.h"
#include "signed_svd.h"

#include <Eigen/Core>

namespace PeriSISSM {

// First Piola-Kirchhoff stress P = dW/dF = U diag(Phat(s)) V^T.
//
// Inputs:  material, F 3x3 deformation gradient (any F; see signed_svd()).
// Outputs: P (3x3, stress units: force per reference area).
Eigen::Matrix3d first_piola(const Material& material, const Eigen::Matrix3d& F);

// Everything one particle needs from its deformation gradient, from a single SVD.
// Fixed-size members only: no heap allocation.
struct ParticleStress {
  SignedSVD svd;                // F = U diag(s) V^T
  double J;                     // det F = s_1 s_2 s_3 (dimensionless)
  double W;                     // strain energy density W(F) (stress units)
  Eigen::Matrix3d P;            // first Piola-Kirchhoff stress U diag(Phat) V^T
  Eigen::Matrix3d P_implicit;   // implicit part P^+ = U diag(c .* s) V^T
  Eigen::Matrix3d stiffness;    // U diag(c) U^T: symmetric PSD; stiffness * F == P^+
};

// Per-particle stress evaluation.
//
// Inputs:  material, F 3x3 deformation gradient.
// Outputs: out (all members overwritten). The explicit part of the stress is
//          out.P - out.P_implicit. With eta ~= F xi, P^+ K^-1 xi ~= (U diag(c) U^T) F K^-1 xi,
//          and H_i = kappa_i * out.stiffness is the particle's implicit stiffness (math.md 2).
void particle_stress(const Material& material, const Eigen::Matrix3d& F, ParticleStress& out);

}  // namespace PeriSISSM

#endif  // PERISISSM_STRESS_H
