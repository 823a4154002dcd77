// The elastic (correspondence) energy term (doc/theory.rst, "Correspondence"). For particle i
// with family H_i:
//   K_i = sum_j omega_ij xi (x) xi,    M_i = sum_j omega_ij eta (x) xi,    F_i = M_i K_i^-1
//   E = sum_i V_i W(F_i)
// and the exact force density f_k = -(1/V_k) dE/dy_k:
//   f_i = sum_j omega_ij (H_i + H_j) xi,   H_i = P(F_i) K_i^-1 (+ Q_i K_i^-1 from the
//   stabilization term)
// Diagonal block (the SISSM split): sum_j omega_ij (H^+_i + H^+_j) with H^+ the implicit
// stiffness kappa U diag(c) U^T of each end (particle.h).
// A particle whose K is singular has no F: no force state of its own, W = 0, F reported as the
// identity; its bonds still carry the partners' force states.

#ifndef PERISISSM_PERI_ELASTIC_H
#define PERISISSM_PERI_ELASTIC_H

#include "peri/family.h"
#include "peri/fields.h"

#include <vector>

namespace PeriSISSM {

class Model;

// The state pass over the owned particles: bond checks of the breaking rule (mode
// BreakingRule::NOBREAK, S0ONLY or BREAK), then F, A = P K^-1, W and C of each particle into
// fields.g, fields.h, fields.w (and H^+, C into fields.k when blocks is true). A bond that
// breaks gets partner index -1 and the particle's shape is updated at once (it no longer counts
// in this evaluation); the particles that lost bonds are appended to broke. With breaking,
// p.smin is replaced by the smallest stretch of this evaluation.
void elastic_state_pass(const Model &model, const Particles &p, const Families &fam,
                        const ReferenceBox &box, int mode, bool blocks, ParticleFields &fields,
                        std::vector<int> &broke);

// The bond force pass over the owned particles: f_i += sum_j omega (H_i + H_j) xi (needs H of
// the ghosts), and its virial (each end tallies half of (x_i - x_j) (x) V_i f_ij). When block
// is not null (then fields.k of the ghosts is needed too), also the diagonal blocks
//   block_i = sum_j omega_ij (H^+_i + H^+_j + (C_i + C_j)/2 I)   (xx yy zz xy xz yz)
// the elastic term's implicit stiffness plus the stabilization term's (C_i + C_j)/2 omega I
// (for a membrane particle times I - n n^T, n its current normal in fields.normal: its
// stabilization acts in its tangent plane), summed while the particle's bonds are in cache.
void elastic_force_pass(const Particles &p, const Families &fam, const ReferenceBox &box,
                        const ParticleFields &fields, const Virial &virial, double **block);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_ELASTIC_H
