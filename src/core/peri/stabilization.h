// Zero-energy-mode stabilization in bond-averaged form (doc/theory.rst, "Stabilization").
//
// For a bond ij with reference bond xi and current bond eta,
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
// penalized.
//
// Force (exact derivative of the energy): the direct force density Cbar omega z on i, and
// through F_i the stress-like term Q_i = -(1/2) sum_j Cbar omega z (x) xi added to the force
// state: H_i = A_i + Q_i K_i^-1. Diagonal block: Cbar omega I per bond (the stiffness of the
// direct force with respect to eta, with F held).
//
// A particle whose K is singular has no F: its bonds use the partner's F alone (a bond between
// two such particles has no stabilization).
//
// Length form (pair_coeff keyword deviation length; a bond uses it when both ends' types do and
// neither is a membrane): only the deviation of the bond's length from the length Fbar gives it,
//   d_ij = (|eta|^2 - |g|^2) / (2 |xi|),   g = Fbar_ij xi,
// with the energy (Cbar_ij / 2) omega_ij V_i d^2 per bond (d = |eta| - |g| to first order; the
// squared lengths need no square root and stay smooth where eta or g vanish). It is zero for
// affine motion and frame-indifferent like z. Direct force density Cbar omega d eta / |xi| on i,
// and Q_i = -(1/2) sum_j Cbar omega d g (x) xi / |xi| (weights a as above); the diagonal block
// keeps Cbar omega I per bond (an upper bound of the stiffness Cbar omega e e^T along the bond).
// A bond's stabilization then follows its own stretch like a bond-based spring: a bond that
// crosses an opening crack at a shallow angle stores energy only as it is stretched, so the
// stabilization's share of the fracture energy no longer grows with delta/h (breaking.h).
// Measured on a Kalthoff-Winkler plate (2 mm spacing, horizon 3 spacings, G0 22.17 kJ/m^2,
// 90 us): the vector form leaves diffuse damage and no crack, the length form a sharp crack
// from each notch tip at about the angle peri/lps gives (doc/pair_peri_nosb.rst).

#ifndef PERISISSM_PERI_STABILIZATION_H
#define PERISISSM_PERI_STABILIZATION_H

#include "peri/family.h"
#include "peri/fields.h"

namespace PeriSISSM {

class Model;

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

// Membranes: a bond between two membrane particles counts only the part of z in the current
// tangent planes of its ends, with the energy (Cbar / 4) omega V_i z^T (T_i + T_j) z, T = I -
// n n^T and n = F t1 x F t2 / |F t1 x F t2| the particle's current normal (membrane/membrane.h);
// its out-of-plane part would be a bending stiffness that depends on the mesh. Forces stay the
// exact gradient: the direct force is Cbar omega (T_i + T_j) z / 2, Q_i uses that projected z,
// and the dependence of n_i on F_i adds G_i = (a2 x w) (x) t1 + (w x a1) (x) t2 to Q_i, with
// a_k = F_i t_k, w = (I - n n^T) g / |a1 x a2| and g = dE/dn_i = -sum_j (Cbar / 2) omega (n_i .
// z) z (per unit volume). An end whose normal is not defined (singular K) takes the other
// end's.

// The stabilization pass over the owned particles: needs F, C and the regular flag of every
// particle and its ghosts (fields.g), and in decks with membranes their reference normals
// (fam.normal, owned and ghost rows) and p.nall. Adds the direct force density to p.f,
// Q_i K_i^-1 to fields.h, the virial of the direct force (half of each bond to each end), and,
// when energy is true, the energy density to fields.w (left alone otherwise).
// Whether a row of ParticleFields::normal holds a current normal (a membrane particle with an F;
// the rows of the others are zeros).
inline bool has_normal(const double *n) { return n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0; }

void stabilization_pass(const Model &model, const Particles &p, const Families &fam,
                        const ReferenceBox &box, ParticleFields &fields, const Virial &virial,
                        bool energy);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_STABILIZATION_H
