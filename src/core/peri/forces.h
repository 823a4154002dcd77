// One force evaluation of the bond terms (elastic and stabilization) in the order their data
// dependencies need, with the halo exchanges between the passes (doc/theory.rst, "Parallel
// evaluation"):
//   (1) F, C of the owned particles (elastic_state_pass, with the bond checks); halo(F, C)
//   (2) stabilization: direct force, energy, Q (stabilization_pass); halo(H)
//   (3) bond forces f_i = sum_j omega (H_i + H_j) xi (elastic_force_pass)
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
// breaking rule (BreakingRule::NOBREAK, S0ONLY, BREAK); blocks: also the implicit stiffness
// (fields.k) for assemble_blocks(); virial sinks.
// Outputs: p.f (+=), fields (g, h, w, k), p.smin (with breaking), broke (particles that lost
// bonds in this evaluation: their partner index is -1 now; the owner of the family storage
// clears whatever else it keeps about those bonds).
void evaluate_bond_terms(const Model &model, const Particles &p, const Families &fam,
                         const ReferenceBox &box, int mode, bool blocks, ParticleFields &fields,
                         Halo &halo, const Virial &virial, std::vector<int> &broke);

// The SISSM diagonal blocks of the owned particles after an evaluation with blocks:
// halo(k), then implicit_blocks() (elastic.h).
void assemble_blocks(const Families &fam, int nlocal, ParticleFields &fields, Halo &halo,
                     double **block);

}  // namespace PeriSISSM

#endif  // PERISISSM_PERI_FORCES_H
