/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm (doc/theory.rst, "The implicit step"; the time schemes: solvers/time_scheme.h; the
   solvers: solvers/jacobi.h, solvers/newton_krylov.h). The solve runs in post_integrate, after
   every initial_integrate, so particles prescribed by fix move or other integrators already sit
   at t^{n+1}.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "collision_limit.h"
#include "fix_sissm_system.h"

#include "implicit_forces.h"

#include "solvers/carried_rows.h"
#include "solvers/jacobi.h"
#include "solvers/momentum.h"
#include "solvers/newton_krylov.h"
#include "solvers/preconditioner.h"
#include "solvers/step_retry.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;
using PeriSISSM::PrecondKind;
using PeriSISSM::SolverKind;

namespace {

// The implicit step of the force model, ended however the step ends (also when an error is
// thrown inside it and the caller of LAMMPS carries on).
class ImplicitStep {
 public:
  ImplicitStep(ImplicitForces *forces, int groupbit) : forces_(forces)
  {
    forces_->begin_implicit_step(groupbit);
  }
  ~ImplicitStep() { forces_->end_implicit_step(); }
  ImplicitStep(const ImplicitStep &) = delete;
  ImplicitStep &operator=(const ImplicitStep &) = delete;

 private:
  ImplicitForces *forces_;
};

}    // namespace

/* ---------------------------------------------------------------------- */

FixSissm::FixSissm(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  reductions = std::make_unique<WorldReductions>(lmp, world);
  system = std::make_unique<SissmSystem>(this, *reductions);
  time_integrate = 1;
  force_reneighbor = 1;    // after steps that moved atoms far (short-range contact)
  next_reneighbor = -1;
  vector_flag = 1;
  size_vector = 11;
  comm_forward = 1;    // amg: global node numbers of the ghosts
  global_freq = 1;
  extvector = 0;

  // the keywords (doc/fix_sissm.rst), read by solvers/step_options.h
#ifndef PERISISSM_HAVE_PETSC
  opt.precond = PrecondKind::block;    // the default amg needs PETSc (doc/fix_sissm.rst)
#endif
  auto read = [&](const std::string &w, PeriSISSM::WordKind kind) -> double {
    if (kind == PeriSISSM::WordKind::integer) return utils::inumeric(FLERR, w, false, lmp);
    if (kind == PeriSISSM::WordKind::real) return utils::numeric(FLERR, w, false, lmp);
    return utils::logical(FLERR, w, false, lmp);
  };
  const PeriSISSM::StepOptionsProblem bad =
      PeriSISSM::read_step_options({arg + 3, arg + narg}, read, opt);
  if (!bad.missing.empty()) utils::missing_cmd_args(FLERR, bad.missing, error);
  if (!bad.problem.empty()) error->all(FLERR, "Illegal fix sissm command: {}", bad.problem);

  scheme = PeriSISSM::make_time_scheme(opt.scheme, opt.rho_inf);
  scheme->set_error_rule(opt.error > 0.0);
  ncols = scheme->history_columns();
  travels = opt.precond == PrecondKind::amg;
  if (ncols > 0 || travels) {
    // the history (kept in restart files too) and amg's node numbers travel with the atoms
    maxexchange = ncols + (travels ? 1 : 0);
    grow_arrays(atom->nmax);
    atom->add_callback(Atom::GROW);
    for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
  }
  if (ncols > 0) {
    restart_peratom = 1;
    atom->add_callback(Atom::RESTART);
  }
  // the scheme's state and the Newton forcing term carried to the next solve
  if (ncols > 0 || opt.solver == SolverKind::krylov) restart_global = 1;
#ifndef PERISISSM_HAVE_PETSC
  if (opt.precond == PrecondKind::amg)
    error->all(FLERR,
               "Fix sissm precond amg needs PETSc, and this build of the plugin has none "
               "(install Debian's petsc-dev and rebuild, e.g. with tools/setup.sh); "
               "use precond block");
#endif
}

/* ---------------------------------------------------------------------- */

FixSissm::~FixSissm()
{
  if (ncols > 0 || travels) atom->delete_callback(id, Atom::GROW);
  if (ncols > 0) atom->delete_callback(id, Atom::RESTART);
  memory->destroy(hist);
  memory->destroy(gnode);
  destroy_arrays();
}

/* ---------------------------------------------------------------------- */

int FixSissm::setmask()
{
  return POST_INTEGRATE | PRE_REVERSE;
}

/* ---------------------------------------------------------------------- */

void FixSissm::init()
{
  forces = dynamic_cast<ImplicitForces *>(force->pair_match("peri/nosb", 1));
  if (!forces)
    error->all(FLERR, "Fix sissm requires pair_style peri/nosb (found {})",
               force->pair_style ? force->pair_style : "no pair style");
  if (!atom->rmass_flag || !atom->vfrac_flag)
    error->all(FLERR, "Fix sissm requires atom_style peri (per-atom density and volume)");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix sissm does not support run_style respa");
  dtv = update->dt;
  comm_reverse = 3;
  choose_external();
  // a contact that checks every move of the unknowns: the forces at the step's end
  scheme->set_forces_at_end(!limiters.empty());
  if (!limiters.empty() && opt.scheme == "genalpha" && comm->me == 0)
    utils::logmesg(lmp,
                   "Fix sissm {}: scheme genalpha with a contact fix that limits moves: alpha_f "
                   "= 0 (Wood-Bossak-Zienkiewicz), the forces at the end of the step\n",
                   id);
  // contacts that adapt their stiffness to the step (kappa auto) need the scheme's force factor
  // before the first step, for the run's setup evaluation; one integrator may set it
  if (!adapting.empty()) {
    if (modify->get_fix_by_style("^sissm$").size() > 1)
      error->all(FLERR,
                 "Fix sissm {}: a contact fix adapts its stiffness to the implicit step (kappa "
                 "auto), but there is more than one fix sissm: give kappa as a number",
                 id);
    scheme->set_step(dtv);
    for (CollisionLimit *contact : adapting) contact->set_force_factor(scheme->force_factor());
  }
  forces->track_contact_motion(1);
  const std::string note =
      PeriSISSM::settle_for_membranes(opt, forces->has_unbent_membranes(groupbit), id);
  if (!note.empty() && comm->me == 0) utils::logmesg(lmp, note);
  block_precond = std::make_unique<PeriSISSM::BlockPreconditioner>();
  amg_precond.reset();
  if (opt.precond == PrecondKind::amg) amg_precond = make_amg();
  precond = amg_precond ? amg_precond.get() : block_precond.get();
  // the options of this run decide which work arrays exist: allocate them anew
  destroy_arrays();
  nmax = 0;
}

/* ----------------------------------------------------------------------
   collision-free steps and lagged friction (collision_limit.h): the start of a (sub-)step, and
   the limit of every later move; the stiffness of the contacts that adapt it is balanced at
   the first evaluation of the step (balance_first)
------------------------------------------------------------------------- */

void FixSissm::begin_path(double h)
{
  comm->forward_comm();
  for (CollisionLimit *contact : contacts) contact->begin_step(h, scheme->force_factor());
  balance_first = !adapting.empty();
  for (CollisionLimit *limit : limiters) limit->begin_path();
}

// ghost positions current on entry and on return; at the end of a step, a move cut short by
// a contact's reach leaves the step unsettled (end_reach, beyond_reach()): its sub-steps may
// start from new candidates
void FixSissm::limit_path(bool end_of_step)
{
  reach_cut = 0;
  reach_kept = 1.0;
  reach_limiter = nullptr;
  for (CollisionLimit *limit : limiters) {
    const double t = limit->limit_move(groupbit);
    if (t < 1.0) comm->forward_comm();
    if (limit->reach_limited()) {
      if (end_of_step && !end_reach) end_reach = limit;
      reach_cut = 1;
      if (!reach_limiter || t < reach_kept) reach_limiter = limit;
      reach_kept = std::min(reach_kept, t);
    }
  }
  for (CollisionLimit *limit : limiters) limit->begin_path();
}

/* ---------------------------------------------------------------------- */

void FixSissm::reset_dt()
{
  dtv = update->dt;
}

/* ----------------------------------------------------------------------
   the per-atom work arrays: rows of cols doubles (or one double per atom, vector), and whether
   the options of this run use them
------------------------------------------------------------------------- */

struct FixSissm::WorkArray {
  double ***rows;
  double **vector;
  int cols;
  bool used;
  const char *name;
};

std::vector<FixSissm::WorkArray> FixSissm::work_arrays()
{
  const bool lagged = external_mode == PeriSISSM::ExternalMode::lagged ||
      external_mode == PeriSISSM::ExternalMode::mixed;
  // redone steps start again from y^n, v^n; with precond amg too (a switch of preconditioner)
  const bool restart = opt.retry.unconverged == PeriSISSM::Unconverged::cutback ||
      opt.precond == PrecondKind::amg || (scheme && scheme->force_time() < 1.0);
  const bool krylov = opt.solver == SolverKind::krylov, history = ncols > 0;
  return {{&kblock, nullptr, 6, true, "sissm:block"},
          {nullptr, &psize, 1, true, "sissm:size"},
          {&yn, nullptr, 3, true, "sissm:yn"},
          {&yhat, nullptr, 3, true, "sissm:yhat"},
          {&res, nullptr, 3, true, "sissm:res"},
          {&fext, nullptr, 3, true, "sissm:fext"},
          {&moment, nullptr, PeriSISSM::kMomentumColumns, true, "sissm:moment"},
          {&fint, nullptr, 3, lagged, "sissm:fint"},
          {&flagged, nullptr, 3, lagged, "sissm:flagged"},
          {&xstart, nullptr, 3, restart, "sissm:xstart"},
          {&vstart, nullptr, 3, restart, "sissm:vstart"},
          {&hstart, nullptr, ncols, restart && history, "sissm:hstart"},
          {&vn, nullptr, 3, history, "sissm:vn"},
          {&fstart, nullptr, 3, history, "sissm:fstart"},
          {&rprev, nullptr, 3, opt.relax, "sissm:rprev"},
          {&dprev, nullptr, 3, opt.relax, "sissm:dprev"},
          {&yprev, nullptr, 3, opt.chebyshev > 0.0, "sissm:yprev"},
          {&xbase, nullptr, 3, krylov, "sissm:krylov"},
          {&rbase, nullptr, 3, krylov, "sissm:krylov"},
          {&jbase, nullptr, 3, krylov, "sissm:krylov"},
          {&cres, nullptr, 3, krylov, "sissm:krylov"},
          {&zdir, nullptr, 3, krylov, "sissm:krylov"},
          {&pdir, nullptr, 3, krylov, "sissm:krylov"},
          {&sdir, nullptr, 3, krylov, "sissm:krylov"},
          {nullptr, &term, 1, krylov, "sissm:term"}};
}

void FixSissm::destroy_arrays()
{
  for (const WorkArray &w : work_arrays()) {
    if (w.rows) memory->destroy(*w.rows);
    if (w.vector) memory->destroy(*w.vector);
  }
}

void FixSissm::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  for (const WorkArray &w : work_arrays()) {
    if (w.used && w.rows) memory->grow(*w.rows, nmax, w.cols, w.name);
    if (w.used && w.vector) memory->grow(*w.vector, nmax, w.name);
  }
}

/* ----------------------------------------------------------------------
   the per-atom rows of the step (every work array of this run's options; the history travels
   with the atoms by itself), those holding positions marked; for neighbor list builds inside
   a step (fix_sissm_neighbor.cpp)
------------------------------------------------------------------------- */

std::vector<PeriSISSM::CarriedArray> FixSissm::carried_arrays()
{
  std::vector<PeriSISSM::CarriedArray> out;
  for (const WorkArray &w : work_arrays()) {
    if (!w.used) continue;
    PeriSISSM::CarriedArray a;
    a.rows = w.rows ? *w.rows : nullptr;
    a.vector = w.vector ? *w.vector : nullptr;
    a.cols = w.cols;
    a.position = w.rows == &yn || w.rows == &yhat || w.rows == &xstart || w.rows == &xbase ||
        w.rows == &yprev;
    out.push_back(a);
  }
  return out;
}

/* ---------------------------------------------------------------------- */

void FixSissm::setup(int /*vflag*/)
{
  stats = PeriSISSM::StepStatistics();
  warned = warned_roundoff = warned_fallback = 0;
  block_first = 0;
}

/* ----------------------------------------------------------------------
   the run's solver statistics in the log (thermo shows them per step: outputs 1-9)
------------------------------------------------------------------------- */

void FixSissm::post_run()
{
  if (comm->me != 0 || stats.steps == 0) return;
  std::string text = stats.summary(id);
  if (amg_precond && !amg_precond->summary().empty()) text += "; " + amg_precond->summary();
  utils::logmesg(lmp, text + "\n");
}

/* ----------------------------------------------------------------------
   amg: the global node numbers reach the ghosts
------------------------------------------------------------------------- */

int FixSissm::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  for (int k = 0; k < n; k++) buf[k] = gnode[list[k]];
  return n;
}

void FixSissm::unpack_forward_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) gnode[first + k] = buf[k];
}

/* ----------------------------------------------------------------------
   one implicit step of length h for the group from the atoms' current positions and
   velocities (flag: the lagged force density the predictor carries, or null): predictor, solve,
   momentum balance of a free group, end velocities. The evaluations are counted from zero.
------------------------------------------------------------------------- */

PeriSISSM::SolveResult FixSissm::solve_step(double h, double t_end, double **flag)
{
  double **x = atom->x;
  double **v = atom->v;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  scheme->set_step(h);
  // the others where the scheme evaluates the forces (generalized-alpha: t^{n+1-alpha_f}; a
  // sub-step: its end), back at the end of the (sub-)step afterwards
  const double tforce = t_end - (1.0 - scheme->force_time()) * h / dtv;
  const bool move_others = xstart && (tforce < 1.0);
  if (move_others) place_others(tforce);
  if (!contacts.empty()) begin_path(h);    // (the limiters are among the contacts)
  arrays = {x, v, yn, vn, yhat, hist, flag, fstart};
  const PeriSISSM::Rows &rows = system->rows();
  scheme->begin(rows, arrays);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) fext[i][0] = fext[i][1] = fext[i][2] = 0.0;

  system->begin_solve();
  PeriSISSM::SolveResult result;
  if (opt.solver == SolverKind::krylov) {
    const PeriSISSM::KrylovWork work{xbase, rbase, jbase, cres, zdir, pdir, sdir, term, &forcing};
    result = PeriSISSM::solve_newton_krylov(*system, *precond, opt.iterations, work, opt.error);
    // (tolerance 0: every step runs to the limit by request, which says nothing of the
    // preconditioner)
    precond->finished(result.newton, result.krylov, result.converged() || opt.tolerance == 0.0);
  } else {
    result = PeriSISSM::solve_jacobi(*system, opt.iterations, {rprev, dprev, yprev}, opt.chebyshev);
  }
  stats.solved(result);
  // (a solve that the reach stalled ends beyond it, whatever its last move does)
  CollisionLimit *const stalled_by = system->stalled() ? reach_limiter : nullptr;
  if (!forces->group_coupled(groupbit)) {
    const PeriSISSM::MomentumBalance balance{h, scheme->force_factor(), scheme->name() == "euler"};
    PeriSISSM::balance_momentum(rows, *reductions, balance, x, yn, yhat, flag ? nullptr : fext,
                                moment);
  }
  // the last move (the final correction, the momentum balance) is limited like the others
  end_reach = nullptr;
  if (!limiters.empty()) {
    comm->forward_comm();
    limit_path(true);
  }
  if (!end_reach) end_reach = stalled_by;
  scheme->finish(rows, arrays);
  if (move_others) place_others(t_end);
  return result;
}

/* ----------------------------------------------------------------------
   the step as the retry ladder drives it (solvers/step_retry.h): a redone step starts again
   from y^n, v^n; the atoms outside the group sit where place_others() puts them at the end of
   each sub-step, and at t^{n+1} afterwards; the other fixes' forces are those of t^{n+1}.
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class SissmAttempts : public PeriSISSM::StepAttempts {
 public:
  SissmAttempts(FixSissm *fix, double **flag) : fix_(fix), flag_(flag) {}
  PeriSISSM::SolveResult solve(int n, int s) override
  {
    // (a sub-step may start with a neighbor list build, which may move flagged)
    if (n > 1) fix_->start_substep();
    return fix_->solve_step(fix_->dtv / n, (double) (s + 1) / n, flag_ ? fix_->flagged : nullptr);
  }
  int evaluations() const override { return fix_->system->evaluations(); }
  void restore_start() override { fix_->restore_start(); }
  bool refresh_preconditioner() override { return fix_->precond->refresh(); }
  void switch_preconditioner() override
  {
    PeriSISSM::Preconditioner *block = fix_->block_precond.get();
    fix_->precond = (fix_->precond == block) ? fix_->amg_precond.get() : block;
  }
  void end_cutback() override
  {
    fix_->place_others(1.0);
    fix_->scheme->set_step(fix_->dtv);
  }
  bool beyond_reach() override { return fix_->beyond_reach(); }

 private:
  FixSissm *fix_;
  double **flag_;
};
}    // namespace LAMMPS_NS

/* ----------------------------------------------------------------------
   what the retry ladder did, in the statistics and the log; a cutback that did not converge
   ends the run
------------------------------------------------------------------------- */

void FixSissm::report_retries(const PeriSISSM::RetryOutcome &outcome)
{
  const bool now_block = precond == block_precond.get();
  const PeriSISSM::RetryTexts text = PeriSISSM::retry_texts(outcome, context(), now_block);
  if (outcome.switched) {
    if (outcome.switch_converged) block_first = now_block ? PeriSISSM::kBlocksFirstSteps : 0;
    stats.switches++;
    if (!warned_fallback && comm->me == 0) error->warning(FLERR, text.warning);
    warned_fallback = 1;
  }
  if (!outcome.cut_back) return;
  // (a last sub-step that converged beyond the contact candidates' reach: contact_end_of_step()
  // says so)
  if (outcome.cutback_failed && !(outcome.beyond_reach && outcome.result.converged()))
    error->all(FLERR, text.error);
  stats.cutback++;
  if (comm->me == 0) utils::logmesg(lmp, text.note);
}

PeriSISSM::StepContext FixSissm::context() const
{
  return {id, update->ntimestep, opt.iterations, dtv};
}

/* ----------------------------------------------------------------------
   the atoms outside the group at the fraction t of the step; the group back at y^n, v^n and
   the scheme's history of the start of the step (solvers/step_start.h)
------------------------------------------------------------------------- */

void FixSissm::place_others(double t)
{
  PeriSISSM::place_others(system->rows(), step_start(), atom->v, dtv, t, atom->x);
}

void FixSissm::restore_start()
{
  PeriSISSM::restore_start(system->rows(), step_start(), atom->x, atom->v, hist);
  if (!state_start.empty()) scheme->set_state(state_start.data());
}

/* ---------------------------------------------------------------------- */

void FixSissm::post_integrate()
{
  grow();
  double **x = atom->x;
  double **v = atom->v;
  const int nlocal = atom->nlocal;
  const bool lagged = external_mode == PeriSISSM::ExternalMode::lagged;
  const bool mixed = external_mode == PeriSISSM::ExternalMode::mixed;
  PeriSISSM::Rows &rows = system->step_rows();
  rows = {nlocal, atom->mask, groupbit, atom->vfrac, atom->rmass, psize};
  // the particle sizes of the convergence measure, once per step rather than per iteration
  for (int i = 0; i < nlocal; i++) psize[i] = cbrt(atom->vfrac[i]);

  // lagged: fint of ghosts belongs to their owners (short-range contact with newton on)
  if ((lagged || mixed) && force->newton_pair) comm->reverse_comm(this);
  if (lagged || mixed) lagged_external_force();
  if (xstart) PeriSISSM::keep_start(nlocal, x, v, hist, step_start());
  if (ncols > 0) {
    PeriSISSM::keep_start_force(rows, atom->f, fstart, hist, ncols);
    state_start.resize(scheme->state_size());
    if (!state_start.empty()) scheme->get_state(state_start.data());
  }

  stats.begin_step();
  // tolerance 0 asks for every step to use all its iterations: such a step is neither redone
  // nor refused
  opt.retry.fixed_count = opt.tolerance == 0.0;
  opt.retry.two_preconditioners = amg_precond != nullptr;
  PeriSISSM::RetryOutcome outcome;
  {
    ImplicitStep step(forces, groupbit);
    // precond amg: the preconditioner that converged the last step goes first
    precond = (amg_precond && !block_first) ? amg_precond.get() : block_precond.get();
    const bool blocks_went_first = amg_precond && block_first > 0;
    if (block_first > 0) block_first--;
    SissmAttempts attempts(this, lagged ? flagged : nullptr);
    outcome = PeriSISSM::run_retry_ladder(attempts, opt.retry);
    // the blocks that went first did not settle the step either: multigrid first again
    if (blocks_went_first && (outcome.refreshed || outcome.switched || outcome.cut_back))
      block_first = 0;
    report_retries(outcome);
  }
  const PeriSISSM::SolveResult &result = outcome.result;
  const double measure = result.measure;
  const bool converged = result.converged();
  // (every policy: the atoms stopped where the candidates end, which the velocities do not know
  // of)
  if (end_reach) end_reach->reach_error("fix sissm");

  // the blow-up guard of pair peri/nosb, now that the atoms are at y^{n+1} (before LAMMPS
  // decides on a neighbor list build): a diverged step ends in an error, not in LAMMPS's
  // neighbor binning
  forces->check_motion(converged ? 1 : 0);
  // short-range contact: a result beyond what the candidates could follow is refused, and
  // the next step starts from a fresh neighbor list if this one moved atoms far
  const std::string cause = converged ? "" : PeriSISSM::unconverged_cause(measure, tol_step);
  bool rebuild = forces->contact_end_of_step(cause);
  for (CollisionLimit *limit : limiters) rebuild = limit->rebuild_wanted(true) || rebuild;
  if (rebuild) next_reneighbor = update->ntimestep;

  const int evaluations = outcome.evaluations;
  const PeriSISSM::StepVerdict verdict = PeriSISSM::step_verdict(opt.retry, converged);
  // (the scheme keeps it in its state: restart files and redone steps carry it)
  scheme->set_extrapolation(converged);
  stats.end_step(evaluations, measure, outcome.substeps,
                 verdict == PeriSISSM::StepVerdict::converged,
                 result.error_met ? result.error : -1.0);
  if (verdict != PeriSISSM::StepVerdict::converged) {
    if (verdict == PeriSISSM::StepVerdict::error)
      error->all(FLERR, PeriSISSM::unconverged_error(context(), evaluations, measure, tol_step));
    if (!warned && comm->me == 0)
      error->warning(
          FLERR, PeriSISSM::unconverged_warning(context(), evaluations, measure, opt.tolerance));
    warned = 1;
  }
}

/* ---------------------------------------------------------------------- */

double FixSissm::compute_vector(int n)
{
  return stats.output(n);
}

/* ---------------------------------------------------------------------- */

double FixSissm::memory_usage()
{
  // the per-atom arrays grow() allocates and the scheme's history (PETSc's matrix and hierarchy
  // are not counted)
  int arrays = ncols;
  for (const WorkArray &w : work_arrays())
    if (w.used) arrays += w.cols;
  return (double) arrays * nmax * sizeof(double);
}
