/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact inside fix sissm's implicit steps (collision_limit.h says what each call
   promises): lagged friction at x^n, kappa auto's balance and doubling, the path of admissible
   positions and the diagonal stiffness blocks. The rest of the fix is in fix_nosb_contact.cpp.
------------------------------------------------------------------------- */

#include "fix_nosb_contact.h"

#include "contact/barrier_potential.h"
#include "contact/path_limit.h"

#include "atom.h"
#include "error.h"
#include "memory.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;
using PeriSISSM::MotionTracker;

/* ----------------------------------------------------------------------
   kappa auto: a new stiffness (incremental-potential units); the lagged friction's normal
   forces, proportional to it, follow
------------------------------------------------------------------------- */

void FixNosbContact::set_kappa_ip(double k)
{
  const double ratio = k / stiffness.value();
  stiffness.set(k);
  kappa = k / inertia_c;
  for (PeriSISSM::LaggedPair &p : lagged) p.pair.lambda *= ratio;
}

/* ----------------------------------------------------------------------
   kappa auto, at an iterate of fix sissm (the distances of the candidates are current): the
   doubling of the stiffness from the smallest gap over all ranks
------------------------------------------------------------------------- */

void FixNosbContact::adapt_at_iterate()
{
  iterate_pending = 0;
  const double gap = distances.smallest_gap(opt.dmin);
  double all;
  MPI_Allreduce(&gap, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  const double k = stiffness.at_iterate(all);
  if (k != stiffness.value()) set_kappa_ip(k);
}

/* ----------------------------------------------------------------------
   kappa auto, after the first evaluation of a fix sissm (sub-)step: the balance against the
   rest of the residual over the atoms the step moves (the core's balance_sums(), summed over
   the ranks). When no pair is active the stiffness is the lower bound (no force depends on it)
------------------------------------------------------------------------- */

bool FixNosbContact::balance_stiffness(double **res, double force_factor, int igroupbit)
{
  inertia_c = force_factor;
  const PeriSISSM::BalanceSums b =
      PeriSISSM::balance_sums(candidates, distances, atom->x, res, atom->vfrac, atom->mask,
                              igroupbit, atom->nlocal, opt.dhat, opt.dmin);
  // sums over the atoms: res V . grad B, |grad B|^2; lagged friction pairs
  double local[3] = {b.res_dot_grad, b.grad2, (double) lagged.size()}, sums[3];
  MPI_Allreduce(local, sums, 3, MPI_DOUBLE, MPI_SUM, world);
  const double k = stiffness.balanced(sums[0], sums[1]);
  if (k == stiffness.value()) return false;
  set_kappa_ip(k);
  // (no active pair and no friction: no force depends on the stiffness, the evaluation stands)
  return sums[1] > 0.0 || sums[2] > 0.0;
}

/* ----------------------------------------------------------------------
   fix sissm starts a (sub-)step of length h at the current positions x^n (ghosts current): the
   friction of its iterates is lagged here
------------------------------------------------------------------------- */

void FixNosbContact::begin_step(double h, double c)
{
  in_step = 1;
  step_h = h;
  step_start.record(atom->x, atom->nlocal);
  step_start_generation = generation;
  if (opt.kappa_auto) {
    inertia_c = c;
    kappa = stiffness.value() / inertia_c;
    stiffness.begin_step();
  }
  if (opt.mu == 0.0) return;
  if (stale) build_candidates();
  build_lagged();
}

/* ----------------------------------------------------------------------
   fix sissm's path (collision_limit.h): the reference holds owned and ghost positions (no list
   build inside a step); a move is limited by CCD over the candidates (core path_limit.h) and
   by the candidates' reach, skin/2 from the list build (core motion_tracker.h)
------------------------------------------------------------------------- */

void FixNosbContact::begin_path()
{
  const int nall = atom->nlocal + atom->nghost;
  if (nall > nxref) {
    nxref = atom->nmax;
    memory->grow(xref, nxref, 3, "nosb/contact:xref");
  }
  double **x = atom->x;
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) xref[i][d] = x[i][d];
  distances.invalidate();
}

double FixNosbContact::limit_move(int groupbit)
{
  if (stale) build_candidates();
  double **x = atom->x;
  const int nlocal = atom->nlocal;

  // reach: no atom of the group farther than skin/2 from the list build
  const double R = MotionTracker::error_distance(neighbor->skin) * (1.0 - 1.0e-9);
  const MotionTracker::Reach r =
      motion.reach_limit(xref, x, nlocal, atom->mask, this->groupbit, atom->tag, R);
  const double t_reach = r.t;

  // pairs: the largest fraction up to this rank's reach that no candidate pair contradicts
  // (the minimum over ranks is the same as with the pairs' own; all of it, without a look at
  // the pairs, for a move shorter than the gaps allow: a Jacobian product's probe)
  const int nall = nlocal + atom->nghost;
  const double t_pairs = PeriSISSM::move_within_gaps(xref, x, nall, opt.dmin, distances)
      ? 1.0
      : PeriSISSM::path_limit(candidates, xref, x, nall, opt.dmin, &distances, t_reach);

  double mine[2] = {t_pairs, t_reach}, all[2];
  MPI_Allreduce(mine, all, 2, MPI_DOUBLE, MPI_MIN, world);
  const double t = std::min(all[0], all[1]);
  reach_bound = all[1] < 1.0 && all[1] <= all[0];
  if (reach_bound) {
    // the atom that set the reach limit (smallest ID among the ranks that found it)
    const tagint mine_who = (r.atom >= 0 && t_reach == all[1]) ? atom->tag[r.atom] : MAXTAGINT;
    MPI_Allreduce(&mine_who, &reach_atom, 1, MPI_LMP_TAGINT, MPI_MIN, world);
    const double mine_far = (mine_who == reach_atom) ? r.from : 0.0;
    MPI_Allreduce(&mine_far, &reach_moved, 1, MPI_DOUBLE, MPI_MAX, world);
  }
  if (t < 1.0) PeriSISSM::scale_move(xref, x, nlocal, atom->mask, groupbit, t);
  return t;
}

/* ----------------------------------------------------------------------
   an implicit step that ended where the contact candidates' reach cut it short
------------------------------------------------------------------------- */

void FixNosbContact::reach_error(const char *integrator)
{
  error->all(FLERR, "Fix nosb/contact {}: {}", id,
             MotionTracker::reach_error(integrator, update->ntimestep, reach_atom, neighbor->skin,
                                        reach_moved));
}

/* ----------------------------------------------------------------------
   a new neighbor list before the next (sub-)step (motion_tracker.h; fix sissm builds it before
   the forces of that step): at the end of a step once an atom has moved so far from the last
   build that the next step, predicted by the largest move of the last (sub-)step scaled to a
   full step, has less than 1.5 times that left before skin/2 (rebuild_due()); before a
   sub-step, or without a prediction (a build inside the step), once an atom has moved skin/8
------------------------------------------------------------------------- */

bool FixNosbContact::rebuild_wanted(bool end_of_step)
{
  int farthest;
  const int nlocal = atom->nlocal;
  double mine[2] = {motion.largest_move2(atom->x, nlocal, atom->mask, groupbit, farthest), -1.0};
  const bool predict = end_of_step && step_start_generation == generation && step_h > 0.0 &&
      step_start.size() == (std::size_t) nlocal;
  if (predict) mine[1] = step_start.largest_move2(atom->x, nlocal, atom->mask, groupbit, farthest);
  double all[2];
  MPI_Allreduce(mine, all, 2, MPI_DOUBLE, MPI_MAX, world);
  const double skin = neighbor->skin;
  // (every rank predicts or none: the generation and the step are the same on all, and a
  // rank's nlocal changes only with a build, which starts a new generation)
  if (all[1] < 0.0) return all[0] > std::pow(MotionTracker::rebuild_distance(skin), 2);
  const double predicted = std::sqrt(all[1]) * update->dt / step_h;
  return MotionTracker::rebuild_due(std::sqrt(all[0]), predicted, skin);
}

/* ----------------------------------------------------------------------
   the barrier's and the friction's diagonal stiffness blocks of the owned vertices at the
   positions of the last keep_blocks() (barrier_potential.h, friction_potential.h): its active
   pairs and positions, so that the blocks of an iterate can be made after the probes of its
   Jacobian products (their positions differ). The candidates and the lagged friction pairs do
   not change inside a step.
------------------------------------------------------------------------- */

void FixNosbContact::keep_blocks()
{
  const int nall = atom->nlocal + atom->nghost;
  kept_active = active;
  kept_x.resize(3 * (std::size_t) nall);
  kept_rows.resize(nall);
  double **x = atom->x;
  for (int i = 0; i < nall; i++) {
    for (int d = 0; d < 3; d++) kept_x[3 * i + d] = x[i][d];
    kept_rows[i] = &kept_x[3 * i];
  }
  kept_kappa = kappa;
  kept_step_h = step_h;
  kept_friction = opt.mu > 0.0 && in_step && lagged_generation == generation;
}

void FixNosbContact::add_blocks(double **block)
{
  PeriSISSM::barrier_blocks(candidates, kept_active, kept_rows.data(), atom->vfrac,
                            {kept_kappa, opt.dhat, opt.dmin}, block);
  // the friction's (positive semi-definite) blocks at the slip of the kept positions
  if (!kept_friction) return;
  PeriSISSM::friction_blocks(lagged, kept_rows.data(), {opt.mu, opt.epsv * kept_step_h},
                             atom->vfrac, block);
}
