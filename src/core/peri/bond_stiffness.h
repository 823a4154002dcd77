// The bond-projected stiffness (doc/theory.rst, "The coarse level"): a sparse symmetric
// positive semi-definite matrix spectrally equivalent to the correspondence tangent, for an
// algebraic multigrid preconditioner. Every unbroken bond (i, j) of the owned particles acts as
// a spring along its current direction e = eta / |eta| (geometric terms dropped, so the matrix
// stays positive semi-definite and all six rigid-body modes are its exact zero modes):
//   V_i P_ij = -k_ij e e^T  (j != i),     V_i P_ii = sum_j k_ij e e^T,
//   k_ij = c_bb V_i omega_ij e^T (H+_i + H+_j) e,
// H+ the implicit stiffness of each end (particle.h; kappa (2 mu + lambda) I for the linear
// model) and omega_ij = w beta V_j the bond weight, so that k_ij = k_ji.
// Calibration c_bb = 5/3: with H+ = kappa c I, kappa = 15 / (4 pi delta^5) (w = 1, full
// sphere), the springs store under a uniform strain eps the energy density
//   W = (c_bb 2 kappa c) pi delta^5 / 75 (tr(eps)^2 + 2 eps:eps),
// an isotropic material with lambda = mu (nu = 1/4) whose P-wave modulus 2 mu + lambda equals
// c: the springs match the material's stiffness along a bond.
//
// Membranes: a bond with a membrane end also carries the tangent of the stabilization's force
// with the ends' F held fixed (peri/stabilization.h: the force density C omega (I - (n_a n_a^T
// + n_b n_b^T) / 2) z on the part z = eta - Fbar xi of the bond that F does not explain, n_a and
// n_b the current normals of its ends, an end without one taking the other's):
//   S_ij = V_i omega_ij (C_i + C_j) / 2 (I - (n_a n_a^T + n_b n_b^T) / 2),
// added as V_i P_ij -= S_ij, V_i P_ii += S_ij (S_ij = S_ji). It is positive semi-definite and
// keeps the translations as zero modes, not the rotations (F held fixed); it is the stiffness
// across the bond that the springs lack where the correspondence energy has none (measured
// 2026-11-30, fix sissm genalpha at 2 ms, evaluations per step: hanging cloth 3038 vertices
// 10.21 against 10.66, 33418 vertices on 2 ranks 18.87 against 21.05 at 0.93 of the loop time,
// twisting cloth 42.3 against 45.5; the static plate of examples/membranes, alternate
// triangles, Cs = 2, 74.8 against 92.3; but the heavy clamped plate of the tests, turned far in
// six static steps, 636.5 against 547.8). Solids keep the springs alone.

#ifndef PERISISSM_PERI_BOND_STIFFNESS_H
#define PERISISSM_PERI_BOND_STIFFNESS_H

#include "peri/family.h"
#include "peri/fields.h"

#include <vector>

namespace PeriSISSM {

constexpr double kBondProjectionFactor = 5.0 / 3.0;

// The springs of the owned particles, bond by bond in family order (unbroken bonds only).
struct BondSprings {
  std::vector<int> first;      // nlocal + 1 offsets: the springs of particle i are
                               //   first[i] .. first[i+1]-1
  std::vector<int> partner;    // local index of the partner (owned or ghost)
  std::vector<double> k;       // k_ij (energy / length^2)
  std::vector<double> e;       // unit direction, 3 per spring
  std::vector<double> s;       // membranes (fields.normal given): S_ij, 6 per spring (xx yy zz
                               //   xy xz yz; zeros for a bond with no membrane end); else empty
};

// Inputs: families; p (x current for owned and ghost rows, volume); fields.k (H+ and C of
// owned and ghost rows, as after an evaluation with blocks); fields.normal (the current normals
// of membrane particles, owned and ghost rows, zeros for others, as after that evaluation; null
// without membranes); values: false for the springs' partners alone (the matrix's pattern;
// k, e and s left empty).
// Outputs: springs (resized; one entry per unbroken bond of the owned particles). A bond of
// zero current length gets e = 0 (it adds nothing).
void bond_springs(const Families &fam, const Particles &p, const ParticleFields &fields,
                  bool values, BondSprings &springs);

// The bending hinges of membranes in the same matrix (doc/theory.rst, "The coarse level"):
// a hinge of stiffness c and dihedral angle theta (membrane/hinge.h) adds its Gauss-Newton
// Hessian 2 c grad(theta) grad(theta)^T, a 12 x 12 coupling of its four vertices. It is
// positive semi-definite with the rigid-body modes in its null space (theta is invariant), so
// the matrix keeps both properties. Without it the matrix of a membrane has no out-of-plane
// stiffness but the mass, and a fine cloth's bending (D h^2 / (rho_A a^4) of order one at a
// few mm) is left to the Krylov iterations (measured: 35 per Newton step against 8 without
// bending, 33K vertices).
struct HingeCouplings {
  std::vector<int> vertex;     // 4 local indices per hinge (owned or ghost), in hinge order
  std::vector<int> row;        // 4 per hinge: the owned index whose row takes vertex v's part,
                               //   -1 for none on this rank
  std::vector<double> grad;    // 12 per hinge: sqrt(2 c) d theta / d x_v, v = 0..3
  int count() const { return (int) vertex.size() / 4; }
};

// The plate bending of membranes in the same matrix: the mid-edge curvature energy is a sum
// over triangles of a quadratic form in the positions of a stencil of m vertices (the triangle
// and its neighbours, m about 9 to 15), so its Hessian is constant: with a factor a_k (3
// numbers per stencil vertex k) of the element,
//   H_kl = (a_k . a_l) I_3,
// the block between stencil vertices k and l. It is positive semi-definite (the Gram matrix of
// the a_k times I_3) with the rigid-body modes in its null space, so the matrix keeps both
// properties; it is added as it is (no Gauss-Newton step needed).
struct PlateCouplings {
  std::vector<int> first;     // count() + 1 offsets: element e's entries are
                              //   first[e] .. first[e+1]-1, first[0] = 0
  std::vector<int> vertex;    // local index of each entry's vertex (owned or ghost)
  std::vector<int> row;       // per entry: the owned index whose row takes the vertex's part,
                              //   -1 for none on this rank
  std::vector<double> a;      // 3 per entry: the factor a_k
  int count() const { return first.empty() ? 0 : (int) first.size() - 1; }
};

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_BOND_STIFFNESS_H
