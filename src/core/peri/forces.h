// One force evaluation of the bond terms (elastic and stabilization) in the order their data
// dependencies need, with the halo exchanges between the passes (doc/theory.rst, "Parallel
// evaluation"):
//   (1) F, C of the owned particles (elastic_state_pass, with the bond checks; with blocks also
//       the implicit stiffness k); halo(F, C [, k]): one exchange
//   (2) stabilization: direct force, energy, Q (stabilization_pass); halo(H)
//   (3) bond forces f_i = sum_j omega (H_i + H_j) xi, and with blocks the SISSM diagonal
//       blocks in the same pass (elastic_force_pass)
// Three exchanges of particle fields per evaluation with blocks (x, g with k, H), two without.
// Each owned particle sums its own bonds, so no reverse communication is needed, and per-particle
// results do not depend on how the particles are spread over ranks (families are sorted).
// Without stabilization, (2) and its exchange are skipped.

#ifndef PERISISSM_PERI_FORCES_H
#define PERISISSM_PERI_FORCES_H

#include "peri/family.h"
#include "peri/fields.h"

#include <vector>

namespace PeriSISSM {

class Model;

// Inputs: model, particles (forces accumulated into p.f), families, reference box; mode of the
// breaking rule (BreakingRule::NOBREAK, S0ONLY, BREAK); block: null, or one row of 6 per owned
// particle for the SISSM diagonal blocks (elastic.h); virial sinks.
// Outputs: p.f (+=), fields (g, h, w; with block also k, of the ghosts too), block rows,
// p.smin (with breaking), broke (particles that lost bonds in this evaluation: their partner
// index is -1 now; the owner of the family storage clears whatever else it keeps about those
// bonds).
void evaluate_bond_terms(const Model &model, const Particles &p, const Families &fam,
                         const ReferenceBox &box, int mode, double **block, ParticleFields &fields,
                         Halo &halo, const Virial &virial, std::vector<int> &broke);

// The potential energy tallied per particle (W plus its stabilization energy density, as the
// built-in PERI styles tally densities): w[0 .. n - 1] summed in order into *total and added to
// peratom[i]; either may be null.
void tally_energy_densities(int n, const double *w, double *total, double *peratom);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FORCES_H
