// Short-range contact between particles that are not bonded (never were, or whose bond broke),
// as the built-in PERI styles of LAMMPS do for all pairs (doc/theory.rst, "Short-range
// contact"): a repulsive spring acts when
//   r < d = min(0.9 |X_i - X_j|, 1.35 h),   h = mean particle size V^(1/3),
// with stiffness kc = 15 * 18 K / (pi delta^5) (per unit volume squared). The energy of a pair
// and its force densities (f_k = -(1/V_k) dE/dy_k) are
//   E = 1/2 kc V_i V_j (d - r)^2,   f_i = kc V_j (d - r) (x_i - x_j) / r,
// so V_i f_i = -V_j f_j. Bonded pairs are left to the material model, so that an affine
// deformation gives exactly W(F) also under compression.

#ifndef PERISISSM_PERI_CONTACT_H
#define PERISISSM_PERI_CONTACT_H

#include "peri/family.h"
#include "peri/fields.h"

namespace PeriSISSM {

class Model;

// Contact distance of a pair: d = min(0.9 |xi|, 0.675 (V_i^(1/3) + V_j^(1/3))).
double contact_distance(double xi_length, double vi, double vj);
// Energy of a pair at distance r < d (0 beyond), kc = kcontact / horizon.
double contact_energy(double r, double d, double kc, double vi, double vj);
// Force density on i of a pair along del = x_i - x_j at r = |del| < d: f_i = fpair * del.
inline double contact_fpair(double r, double d, double kc, double vj)
{
  return -kc * vj * (r - d) / r;
}
// Diagonal block of the pair for particle i, the positive semi-definite part of -df_i/dx_i:
//   -df_i/dx_i = kc V_j (n n^T + (1 - d/r) (I - n n^T)),   n = del / r,
// whose transverse part (1 - d/r) < 0 for every pair in contact (r < d) is left out, as
// projected Newton does, so the block is kc V_j n n^T (xx yy zz xy xz yz). Like the bond terms'
// blocks (c_k >= 0) it stays positive semi-definite however far a pair is compressed: with the
// exact block a block crushed to 0.1 of its size (d/r ~ 9) gets indefinite blocks, and neither
// preconditioner of fix sissm converges its first step.
void contact_block(const double del[3], double kc, double vj, double block[6]);

// Candidate pairs: for each ii < inum the particle ilist[ii] and its candidates
// neigh[first[ii] .. first[ii+1]-1] (local indices, owned or ghost).
struct ContactCandidates {
  int inum = 0;
  const int *ilist = nullptr;
  const int *first = nullptr;
  const int *neigh = nullptr;
};

// What the caller knows about a pair and where the energy and virial go.
class ContactPairs {
 public:
  virtual ~ContactPairs() = default;
  virtual bool bonded(int i, int j) const = 0;    // an unbroken bond joins i and j
  virtual void acting(int /*i*/, int /*j*/) {}    // a contact pair acts (for counters)
  // energy of the pair as a sum of energy densities (2 E / (V_i + V_j)), force between them
  // (V_i |f_i| / r), and the pair's separation x_i - x_j
  virtual void tally(int i, int j, double energy, double fpair, double dx, double dy,
                     double dz) = 0;
};

// The contact pass: forces of every candidate pair closer than reach (owned i; j also gets its
// force when newton is set or j is owned), reported to pairs.tally when tally is set. When
// block is not null (6 per row, owned and ghost: xx yy zz xy xz yz), each acting pair also adds
// its contact_block() to the rows that get its forces (the caller folds ghost rows into their
// owners as it folds the forces).
void contact_pass(const Model &model, const Particles &p, const ReferenceBox &box, double reach,
                  const ContactCandidates &cand, bool newton, bool tally, ContactPairs &pairs,
                  double *block = nullptr);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_CONTACT_H
