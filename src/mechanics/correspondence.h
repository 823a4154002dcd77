// Correspondence (non-ordinary state-based) peridynamics helpers: the shape tensor, the
// per-particle force-state matrix, the partial-volume factor, the stabilization modulus and the
// Cauchy stress (math.md section 1). LAMMPS-free; 3x3 matrices are passed as plain row-major
// double[9] so that LAMMPS glue code can keep them in its own per-atom arrays.

#ifndef PERISISSM_CORRESPONDENCE_H
#define PERISISSM_CORRESPONDENCE_H

namespace PeriSISSM {

class Material;

// Smallest accepted ratio lambda_min(K) / lambda_ref for a shape tensor K, where lambda_ref is
// the larger of lambda_max(K) and a reference value (the largest eigenvalue of the particle's
// initial, intact K). Below it K counts as singular: the family spans fewer than three
// directions (no partners, one or two partners, all partners coplanar or collinear), or
// fracture has left it so flat or so small that F would amplify noise in its weakest
// direction by more than 1/kMinShapeConditioning, and the particle's correspondence stiffness
// (which grows like 1/lambda_min(K)) would exceed that of its intact state by as much, which
// breaks the explicit time step chosen for the intact body. Intact bodies at least two
// particles thick stay well above it (on a simple cubic lattice with horizon 3a: interior 1,
// face 0.77, edge 0.36, corner 0.28, corner of a two-layer plate 0.11).
constexpr double kMinShapeConditioning = 0.05;

// Inverse of a shape tensor, with the singularity test above.
//
// Inputs:  K (row-major 3x3, symmetric positive semi-definite, units volume * length^2);
//          lambda_ref >= 0 reference eigenvalue (same units; 0 = none).
// Outputs: Kinv (row-major 3x3, symmetric) = K^-1 when K is regular, else all zeros;
//          lambda_max (if not null) the largest eigenvalue of K.
//          Returns true when K is regular: everything finite, lambda_max > 0 and
//          lambda_min >= kMinShapeConditioning * max(lambda_max, lambda_ref).
bool invert_shape_tensor(const double K[9], double lambda_ref, double Kinv[9],
                         double *lambda_max = nullptr);

// Partial-volume factor beta of a bond of reference length r in a horizon delta, for particles
// of size h (edge of a cube of the particle's volume). The partner's cube is taken as cut by the
// sphere of radius delta along the bond direction only (the rule of LAMMPS's PERI styles):
//   beta = 1                         for r <= delta - h/2,
//   beta = (delta + h/2 - r) / h     for delta - h/2 < r <= delta + h/2,
//   beta = 0                         beyond.
// Inputs:  r >= 0, delta > 0, h > 0 (all length). Outputs: beta in [0, 1].
double partial_volume_factor(double r, double delta, double h);

// Zero-energy-mode stabilization (math.md section 1), in the bond-averaged form used by
// pair peri/nosb. For a bond ij with reference bond xi and current bond eta,
//   z_ij = eta - Fbar_ij xi,   Fbar_ij = (F_i + F_j) / 2,
//   energy of the bond  (Cbar_ij / 2) omega_ij V_i |z_ij|^2,   Cbar_ij = (C_i + C_j) / 2,
// counted once per bond (a quarter of Cbar omega |z|^2 goes to the energy density of each
// end). z vanishes for affine motion like eta - F_i xi does, but unlike it also for any
// quadratic displacement field in the bulk (Fbar xi is then the bond's midpoint gradient
// times xi, exact to second order), so the control leaves smooth deformations nearly alone.
// Measured on a pure-bending field of a beam seven particles (two horizons) thick, horizon
// 3 spacings: the one-sided residual eta - F_i xi raised the energy by 17% at Cs = 0.1 and by
// 84% at Cs = 0.5; z raises it by 1.2% per 0.1 of Cs (23% at Cs = 2), less for thicker
// bodies (the excess comes from the surface layers and scales like (delta/thickness)^2).
// Zero-energy modes (eta != F xi at the particle scale) keep |z| ~ |eta - F xi| and are
// penalized. The force follows from the energy exactly (pair_peri_nosb.cpp).
//
// Stabilization modulus C_i: Cs times the bond-based (PMB) micromodulus per unit bond length,
// 18 K / (pi delta^5) (influence function w = 1), scaled by the particle's own shape tensor
// relative to a full family,
//   C_i = Cs * 18 K / (pi delta^5) * kappa_i / kappa_0,   kappa = tr(K^-1) / 3,
//   kappa_0 = 15 / (4 pi delta^5) (full sphere, w = 1)   =>   C_i = (8/5) Cs K tr(K_i^-1).
// In the bulk C_i = Cs 18K/(pi delta^5); where the family is cut by a surface or by broken
// bonds, K_i^-1 grows and C_i with it, so the stabilization stays in proportion to the
// correspondence stiffness P K^-1 (a fixed C let damaged particles with lopsided families go
// unstable and feed energy into the fracture zone).
// Inputs:  Cs >= 0 (dimensionless), K bulk modulus (stress), Kinv (row-major K_i^-1 of a
//          regular shape tensor, 1 / (volume length^2)).
// Outputs: C_i (stress / length^5).
double stabilization_modulus(double Cs, double K, const double Kinv[9]);

// Per-particle state of the correspondence model from the moment M = sum_j w V_j eta (x) xi:
//   F = M K^-1,  P = dW/dF (signed SVD, material),  A = P K^-1,
// so that the particle's correspondence force state on a bond is T<xi> = w A xi.
// Inputs:  material; M (row-major 3x3, volume * length^2); Kinv (row-major, K^-1 of the
//          particle, regular).
// Outputs: F (row-major 3x3, dimensionless), A (row-major 3x3, stress / (volume length^2)),
//          returns the strain energy density W(F) (stress units).
double correspondence_state(const Material& material, const double M[9], const double Kinv[9],
                            double F[9], double A[9]);

// The same, plus the particle's implicit stiffness of the SISSM split (math.md section 2):
// with eta ~= F xi, the implicit part of the force state is
//   w U diag(c .* s) V^T K^-1 xi ~= w kappa U diag(c) U^T eta,   kappa = tr(K^-1) / 3,
// so H = kappa U diag(c) U^T (symmetric positive semi-definite because c >= 0).
// Outputs (in addition): H as xx yy zz xy xz yz (stress / (volume length^2)).
double correspondence_state(const Material& material, const double M[9], const double Kinv[9],
                            double F[9], double A[9], double H[6]);

// Cauchy stress sigma = P F^T / J, from one signed SVD of F: P F^T = U diag(Phat .* s) U^T is
// the Kirchhoff stress tau (exactly symmetric). For J = det F below kCauchyMinJ (collapsed or
// inverted particles, where the current volume is not positive) the divisor is kCauchyMinJ, so
// sigma stays finite, continuous at the threshold, and keeps the sign of tau.
// Inputs:  material; F (row-major 3x3).
// Outputs: sigma as xx yy zz xy xz yz (stress units); J = det F; returns W(F).
constexpr double kCauchyMinJ = 1.0e-3;
double cauchy_stress(const Material& material, const double F[9], double sigma[6], double& J);

// Von Mises equivalent stress of a symmetric stress given as xx yy zz xy xz yz:
//   sqrt( ((sxx-syy)^2 + (syy-szz)^2 + (szz-sxx)^2)/2 + 3 (sxy^2 + sxz^2 + syz^2) ).
double von_mises(const double sigma[6]);

}  // namespace PeriSISSM

#endif  // PERISISSM_CORRESPONDENCE_H
