// The correspondence of one particle: from its deformation gradient F (or the moment M of its
// bonds) to the first Piola-Kirchhoff stress, the strain energy density, the force-state matrix
// A = P K^-1, the implicit stiffness of the SISSM split and the Cauchy stress, all from a single
// signed SVD (doc/theory.rst, "Correspondence" and "The SISSM split"). One pipeline: every
// caller, the LAMMPS pair style and the tests alike, goes through particle_stress().
//
// LAMMPS-free. 3x3 matrices crossing into per-atom arrays are plain row-major double[9];
// symmetric ones are double[6] in the order xx yy zz xy xz yz.

#ifndef PERISISSM_PERI_PARTICLE_H
#define PERISISSM_PERI_PARTICLE_H

#include "linalg/signed_svd.h"

#include <Eigen/Core>

namespace PeriSISSM {

class Material;

// Everything one particle needs from its deformation gradient, from one signed SVD.
// Fixed-size members only: no heap allocation.
struct ParticleStress {
  SignedSVD svd;           // F = U diag(s) V^T
  Eigen::Vector3d phat;    // principal stresses dW/ds
  Eigen::Vector3d c;       // implicit coefficients c >= 0 (zero unless asked for)
  double W;                // strain energy density W(F) (stress units)
  Eigen::Matrix3d P;       // first Piola-Kirchhoff stress U diag(phat) V^T
};

// Per-particle stress evaluation.
//
// Inputs:  material; F 3x3 deformation gradient (any F, see signed_svd());
//          with_split: also the implicit coefficients c of the SISSM split.
// Outputs: out (every member overwritten; c = 0 without with_split).
// P = dW/dF: for isotropic W(F) = W(s(F)), ds_k/dF = u_k v_k^T (also for signed singular
// values), so P = sum_k phat_k u_k v_k^T. At repeated singular values U, V are not unique but P
// is, since a symmetric W gives phat_i = phat_j when s_i = s_j.
void particle_stress(const Material &material, const Eigen::Matrix3d &F, ParticleStress &out,
                     bool with_split = false);

// The same from the signed SVD of F (fast_signed_svd(F): particle_stress() is exactly this).
void stress_from_svd(const Material &material, const SignedSVD &svd, ParticleStress &out,
                     bool with_split = false);

// First Piola-Kirchhoff stress P = dW/dF (particle_stress().P).
Eigen::Matrix3d first_piola(const Material &material, const Eigen::Matrix3d &F);

// Implicit part of the stress P^+ = U diag(c .* s) V^T (needs with_split); the explicit part is
// P - P^+.
Eigen::Matrix3d implicit_part(const ParticleStress &ps);

// Direction of the implicit stiffness, D = U diag(c) U^T symmetrized to the last bit (needs
// with_split): symmetric positive semi-definite, and D F = U diag(c) U^T U diag(s) V^T = P^+,
// so with eta ~= F xi the implicit bond force is linear in eta.
Eigen::Matrix3d implicit_direction(const ParticleStress &ps);

// Implicit stiffness of the split, H = kappa U diag(c) U^T (needs with_split), as xx yy zz xy
// xz yz. With eta ~= F xi the implicit force state w P^+ K^-1 xi = w U diag(c .* s) V^T K^-1 xi
// is w kappa U diag(c) U^T eta when K^-1 = kappa I (an isotropic family; kappa = tr(K^-1)/3 in
// general), so H is the particle's share of the bond stiffness that SISSM treats implicitly;
// symmetric positive semi-definite because c >= 0.
void implicit_stiffness(const ParticleStress &ps, double kappa, double H[6]);

// The particle state of the correspondence model from the moment M = sum_j omega eta (x) xi:
//   F = M K^-1,  P = dW/dF,  A = P K^-1,
// so that the particle's force state on a bond is T<xi> = omega A xi.
// Inputs:  material; M (row-major 3x3, volume length^2); Kinv (row-major K^-1, regular).
// Outputs: F (row-major, dimensionless), A (row-major, stress / (volume length^2)); when H is
//          not null also H = implicit_stiffness(kappa = tr(K^-1)/3). Returns W(F).
double correspondence_state(const Material &material, const double M[9], const double Kinv[9],
                            double F[9], double A[9], double H[6] = nullptr);

// The arguments of one correspondence_state() call; W receives its return value.
struct CorrespondenceState {
  const Material *material;
  const double *M;
  const double *Kinv;
  double *F;
  double *A;
  double *H;    // may be null
  double *W;
};

// Two correspondence_state() calls at once, each with exactly the results it has alone: their
// two SVDs run side by side (fast_svd.h), about 1.4x the throughput of one after the other.
void correspondence_states(const CorrespondenceState &a, const CorrespondenceState &b);

// Four at once, the same way: their SVDs one per lane of 4-wide registers where the processor
// has AVX2 (fast_svd.h), about 1.7x the throughput of two pairs.
void correspondence_states(const CorrespondenceState (&s)[4]);

// Cauchy stress sigma = P F^T / J from one signed SVD: P F^T = U diag(phat .* s) U^T is the
// Kirchhoff stress tau (exactly symmetric). For J = det F below kCauchyMinJ (collapsed or
// inverted particles, whose current volume is not positive) the divisor is kCauchyMinJ, so sigma
// stays finite, continuous at the threshold, and keeps the sign of tau.
// Inputs:  material; F (row-major 3x3).
// Outputs: sigma as xx yy zz xy xz yz (stress units); J = det F; returns W(F).
constexpr double kCauchyMinJ = 1.0e-3;
double cauchy_stress(const Material &material, const double F[9], double sigma[6], double &J);

// Von Mises equivalent stress of a symmetric stress given as xx yy zz xy xz yz:
//   sqrt( ((sxx-syy)^2 + (syy-szz)^2 + (szz-sxx)^2)/2 + 3 (sxy^2 + sxz^2 + syz^2) ).
double von_mises(const double sigma[6]);

// The per-atom columns of compute nosb/atom (doc/compute_nosb_atom.rst) of one particle:
// damage, W, J = det F, von Mises, Cauchy stress xx yy zz xy xz yz, stable explicit time step.
namespace NosbAtom {
  enum Column {
    DAMAGE = 0,
    ENERGY,
    JACOBIAN,
    VONMISES,
    SXX,
    SYY,
    SZZ,
    SXY,
    SXZ,
    SYZ,
    DTSTABLE,
    NCOLUMNS
  };
}
// Inputs:  the material of its type; whether its shape tensor is regular; F (row-major 3x3) and
//          w, its energy density, at the last evaluation (read only when regular); its damage
//          and stable time step.
// Outputs: row[NosbAtom::NCOLUMNS]; a singular particle reports W = 0, J = 1 and zero stress.
void nosb_atom_row(const Material &material, bool regular, const double F[9], double w,
                   double damage, double dtstable, double row[NosbAtom::NCOLUMNS]);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_PARTICLE_H
