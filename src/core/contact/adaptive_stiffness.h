// IPC's adaptive barrier stiffness (Li et al. 2020, supplement; barrier.h's
// initial_barrier_stiffness() and update_barrier_stiffness()) as a rule with its state, for an
// implicit step whose incremental potential has the mass matrix as the inertia's Hessian.
//
// The stiffness kappa_ip is kept in the units of that incremental potential; a force-based
// integrator uses kappa = kappa_ip / c (c the scheme's force factor, h^2 for backward Euler).
// - Bounds from the scene (set_scene()): the diagonal of the bounding box and the mean mass give
//   [kappa_min, 100 kappa_min]; the stiffness starts at kappa_min.
// - The balance (balanced()), at the first iterate of a step: the stiffness that minimises
//   |grad E + kappa grad B| (E the incremental potential without the barrier, B the barrier sum
//   at unit stiffness), clamped to the bounds. With the residual -res_i V_i the gradient of the
//   whole potential, grad E = -res V - kappa_ip grad B; balance_sums() gives the dot products.
// - The doubling (at_iterate()), at later iterates: kappa doubles (up to kappa_max) while the
//   smallest gap is below 1e-9 of the diagonal and still shrinking from the step's last iterate
//   (begin_step() forgets it).
// LAMMPS-free; the caller sums over its ranks.

#ifndef PERISISSM_CONTACT_ADAPTIVE_STIFFNESS_H
#define PERISISSM_CONTACT_ADAPTIVE_STIFFNESS_H

#include "contact/candidate_distances.h"

#include <cmath>
#include <string>

namespace PeriSISSM {

class AdaptiveStiffness {
 public:
  // the scene's scales (the first setup, or a restart) and dhat: the bounds; the stiffness
  // becomes the lower bound
  void set_scene(double bbox_diagonal, double mean_mass, double dhat);
  bool measured() const { return bbox_diagonal_ > 0.0; }
  // a restart: the kept stiffness, clamped to the bounds of set_scene()
  void restore(double kappa_ip);

  // a step begins: the smallest gap of its iterates is not known yet
  void begin_step() { prev_min_gap = HUGE_VAL; }
  // at an iterate, the smallest gap over all pairs (+inf: none): the doubled stiffness while it
  // is tiny and shrinking, else the same
  double at_iterate(double min_gap);
  // the balanced stiffness from the sums of balance_sums() over all ranks
  double balanced(double res_dot_grad, double grad2) const;
  void set(double kappa_ip) { kappa_ip_ = kappa_ip; }

  double value() const { return kappa_ip_; }
  double lower() const { return kappa_min; }
  double upper() const { return kappa_max; }
  double bbox_diagonal() const { return bbox_diagonal_; }
  double mean_mass() const { return mean_mass_; }

 private:
  double kappa_ip_ = 0.0, kappa_min = 0.0, kappa_max = 0.0;
  double bbox_diagonal_ = 0.0, mean_mass_ = 0.0, dhat_ = 0.0;
  double prev_min_gap = HUGE_VAL;
};

// The scales of set_scene() from atoms: the bounding box of their positions and their mean mass.
// add() the atoms of one rank; the caller reduces lo (min), hi (max) and mass (sum: the masses
// and the count) over its ranks.
struct SceneExtent {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  double hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double mass[2] = {0.0, 0.0};
  void add(const double *x, double m);
  double diagonal() const;
  double mean_mass() const { return mass[0] / mass[1]; }    // NaN without atoms
  // why kappa auto cannot use these scales (a diagonal or a mean mass not > 0); empty if it can
  std::string error() const;
};

// The sums of the balance over the owned atoms i < nlocal with (mask[i] & groupbit):
// res_dot_grad = sum_i res_i V_i . grad_i B and grad2 = |grad B|^2, grad B the gradient of the
// barrier sum at unit stiffness over the candidates whose distance (valid) is within dmin +
// dhat, each owned vertex (Candidate::own) taking its part; active: such a vertex exists (the
// sums are 0 otherwise).
struct BalanceSums {
  double res_dot_grad = 0.0;
  double grad2 = 0.0;
  bool active = false;
};
BalanceSums balance_sums(const std::vector<Candidate> &candidates,
                         const CandidateDistances &distances, const double *const *x,
                         const double *const *res, const double *volume, const int *mask,
                         int groupbit, int nlocal, double dhat, double dmin);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_ADAPTIVE_STIFFNESS_H
