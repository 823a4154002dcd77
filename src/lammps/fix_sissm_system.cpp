/* ----------------------------------------------------------------------
   PERI-SISSM: the nonlinear system of fix sissm's step (see fix_sissm_system.h).
------------------------------------------------------------------------- */

#include "fix_sissm_system.h"

#include "collision_limit.h"
#include "fix_sissm.h"
#include "implicit_forces.h"

#include "solvers/step_report.h"
#include "solvers/step_tolerance.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"

using namespace LAMMPS_NS;

namespace {
// an iterate whose move a contact's reach cut to less than this fraction has stalled: the
// reach puts the farthest atom at its end (motion_tracker.h), so a direction that pushes that
// atom on is cut to nothing at every later iterate (measured: examples/twisting-cloth under
// genalpha, step 120, cut to 5.5e-5, 2e-20, then 0 at the 48 iterates up to its budget; a
// thrown cloth whose step went past the reach: every probe of its CG cut to 4e-9 up to the
// budget)
constexpr double kStalledMove = 1.0e-3;
}    // namespace

/* ----------------------------------------------------------------------
   Reductions over the world communicator
------------------------------------------------------------------------- */

void WorldReductions::max(double *values, int n)
{
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MAX, world_);
}

void WorldReductions::sum(long long *values, int n)
{
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_LONG_LONG, MPI_SUM, world_);
}

double WorldReductions::total_rows() const
{
  return (double) lmp_->atom->natoms;
}

/* ---------------------------------------------------------------------- */

double **SissmSystem::unknowns()
{
  return fix_->atom->x;
}

double **SissmSystem::residual()
{
  return fix_->res;
}

/* ----------------------------------------------------------------------
   one force evaluation at the current positions: ghost positions, the peri/nosb force density
   (without energy/virial; the diagonal blocks only when asked), ghost forces folded back
   (where the pair wrote any), with external implicit the post_force of the other fixes (with
   v the time scheme's velocity of the iterate, so velocity dependent forces such as fix
   viscous are implicit too), then the time scheme's residual r_i = rho_i (yhat_i - y_i) + c f_i
   of the owned atoms of the group into res
------------------------------------------------------------------------- */

void SissmSystem::evaluate(bool blocks)
{
  FixSissm &s = *fix_;
  Atom *atom = s.atom;
  evaluations_++;
  // (the blocks are made anew at an evaluation with blocks; a probe's evaluation keeps them)
  if (blocks) contact_blocks_due_ = false;
  s.comm->forward_comm();
  if (!s.limiters.empty()) s.limit_path(false);
  // an iterate of the solver (a probe of a Jacobian product has no blocks): a contact may
  // change its stiffness here
  if (blocks)
    for (CollisionLimit *contact : s.adapting) contact->next_iterate();
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int groupbit = s.groupbit;

  // an iterate that contact candidates could not follow (the pair's short-range contact, or a
  // move cut short by the reach of a contact fix's candidates) cannot count as converged
  contact_incomplete_ = s.forces->contact_follow_motion() < 0 || s.reach_cut;
  // an iterate that the reach left where the last evaluation was (its farthest atom sits at the
  // reach, and the solve's direction pushes it out), or a Jacobian product's probe that the
  // reach cut at all (a product of a cut move is not J's)
  stalled_ = s.reach_cut && (!blocks || s.reach_kept < kStalledMove);
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  s.forces->evaluate(blocks ? s.kblock : nullptr);
  if (s.forces->ghost_forces()) s.comm->reverse_comm();
  const bool mixed = s.external_mode == PeriSISSM::ExternalMode::mixed;
  if (s.external_mode == PeriSISSM::ExternalMode::implicit || mixed) {
    // the other fixes' force at this iterate, kept in fext (f after minus f before)
    double **fext = s.fext;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        s.scheme->iterate_velocity(i, s.arrays, v[i]);
        for (int k = 0; k < 3; k++) fext[i][k] = f[i][k];
      }
    for (Fix *fix : s.implicit_fixes) fix->post_force(0);
    // (the contacts' blocks at these positions when block() first asks, see there)
    if (blocks && !s.limiters.empty()) {
      for (CollisionLimit *limit : s.limiters) limit->keep_blocks();
      contact_blocks_due_ = true;
    }
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) {
          if (mixed) f[i][k] += s.flagged[i][k];
          fext[i][k] = f[i][k] - fext[i][k];
        }
  }

  const int bad = s.scheme->residuals(rows_, s.yhat, x, f, s.res);
  if (bad >= 0)
    s.error->one(FLERR, "Fix sissm: non-finite position or force of atom {} at step {}",
                 atom->tag[bad], s.update->ntimestep);

  // kappa auto: the barrier's stiffness balanced against the rest of the step's residual at
  // its first evaluation, which is redone when the stiffness changed
  if (s.balance_first) {
    s.balance_first = 0;
    bool changed = false;
    for (CollisionLimit *contact : s.adapting)
      changed = contact->balance_stiffness(s.res, s.scheme->force_factor(), groupbit) || changed;
    if (changed) {
      // (the redo's move is empty: a cut of the first move still makes the iterate incomplete)
      const int incomplete = contact_incomplete_;
      const bool stalled = stalled_;
      evaluate(blocks);
      contact_incomplete_ = contact_incomplete_ || incomplete;
      stalled_ = stalled_ || stalled;
    }
  }
}

/* ----------------------------------------------------------------------
   D_i = rho_i I + h^2 block_i of owned atom i (xx yy zz xy xz yz)
------------------------------------------------------------------------- */

void SissmSystem::block(int i, double D[6]) const
{
  // The contacts' blocks (a PSD projection of each active pair's Hessian) at the positions of
  // the last evaluation with blocks (the contacts keep them: probes of Jacobian products that
  // came since do not change them): made here, at the first block() after it, so that iterates
  // whose blocks nobody asks for (most Newton steps with precond amg) do not pay for them
  if (contact_blocks_due_) {
    for (CollisionLimit *limit : fix_->limiters) limit->add_blocks(fix_->kblock);
    contact_blocks_due_ = false;
  }
  fix_->scheme->block(fix_->atom->rmass[i], fix_->kblock[i], D);
}

/* ---------------------------------------------------------------------- */

void SissmSystem::check_finite()
{
  const int bad = PeriSISSM::first_nonfinite(rows_, fix_->atom->x);
  if (bad >= 0)
    fix_->error->one(FLERR, "Fix sissm: non-finite position of atom {} at step {}",
                     fix_->atom->tag[bad], fix_->update->ntimestep);
}

/* ----------------------------------------------------------------------
   the tolerance this step can meet (asked once, after the first evaluation; the round-off
   floor of solvers/step_tolerance.h, one global max); the first time in a run that the floor
   exceeds the tolerance, a warning says so
------------------------------------------------------------------------- */

double SissmSystem::step_tolerance()
{
  FixSissm &s = *fix_;
  const double asked = s.opt.tolerance;
  const PeriSISSM::StepTolerance t = PeriSISSM::step_tolerance(
      asked, rows_, s.atom->x, s.kblock, s.scheme->force_factor(), reductions_);
  s.tol_step = t.tolerance;
  if (t.roundoff_limited(asked) && !s.warned_roundoff && s.comm->me == 0)
    s.error->warning(FLERR,
                     PeriSISSM::roundoff_warning(s.update->ntimestep, t.reach, t.floor, asked));
  if (t.roundoff_limited(asked)) s.warned_roundoff = 1;
  return s.tol_step;
}

/* ----------------------------------------------------------------------
   y^n of the step (written by the scheme's begin())
------------------------------------------------------------------------- */

double **SissmSystem::start()
{
  return fix_->yn;
}
