/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm (doc/theory.rst, "The implicit step"): per step, for the atoms of the group, the
   implicit problem r_i(y) = rho_i (yhat_i - y_i) + c f_i(y) = 0 of the time scheme (keyword
   scheme, src/core/solvers/time_scheme.h; backward Euler: c = h^2, yhat_i = y_i^n + h v_i^n),
   solved by the SISSM sweeps (solver jacobi, solvers/jacobi.h) or Newton-Krylov (solver krylov,
   solvers/newton_krylov.h), an iteration being one force evaluation. f is the exact peri/nosb
   force density plus, with external implicit (default), the forces of the other fixes
   re-evaluated at y (external lagged: taken at y^n, from the total force of the last
   evaluation minus the pair part captured in pre_reverse, and moved into yhat as c fext / rho).
   The solve runs in post_integrate, after every initial_integrate, so particles prescribed by
   fix move or other integrators already sit at t^{n+1}.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "collision_limit.h"
#include "fix_sissm_system.h"

#include "implicit_forces.h"

#include "linalg/exact_sum.h"
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

#include <cmath>
#include <cstring>
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

// the default preconditioner: amg where the build has PETSc (doc/fix_sissm.rst)
#ifdef PERISISSM_HAVE_PETSC
constexpr bool kDefaultAmg = true;
#else
constexpr bool kDefaultAmg = false;
#endif

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
  size_vector = 9;
  comm_forward = 1;    // amg: global node numbers of the ghosts
  global_freq = 1;
  extvector = 0;

  // the keywords (doc/fix_sissm.rst); their words, ranges and rules are solvers/step_options.h
  using namespace PeriSISSM;
  opt.precond = kDefaultAmg ? PrecondKind::amg : PrecondKind::block;
  int iarg = 3;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (!is_step_keyword(key))
      error->all(FLERR, "Illegal fix sissm command: unknown keyword '{}' (allowed: {})", key,
                 utils::join_words(kStepKeywords, ", "));
    if (iarg + 2 > narg || (key == "lagged" && is_step_keyword(arg[iarg + 1])))
      utils::missing_cmd_args(FLERR, "fix sissm " + key, error);
    const char *value = arg[iarg + 1];
    iarg += 2;
    auto choose = [&](const std::vector<std::string> &words) {
      const int k = choice_index(value, words);
      if (k < 0)
        error->all(FLERR, "Illegal fix sissm command: {} must be {}, got '{}'", key,
                   choice_text(words), value);
      return k;
    };
    if (key == "iterations") {
      opt.iterations = utils::inumeric(FLERR, value, false, lmp);
    } else if (key == "tolerance") {
      opt.tolerance = utils::numeric(FLERR, value, false, lmp);
    } else if (key == "relax") {
      opt.relax = utils::logical(FLERR, value, false, lmp);
    } else if (key == "solver") {
      opt.solver = (SolverKind) choose(kSolverWords);
    } else if (key == "external") {
      opt.implicit_external = choose(kExternalWords) == 0;
    } else if (key == "lagged") {
      // the fix IDs up to the next keyword
      for (iarg--; iarg < narg && !is_step_keyword(arg[iarg]); iarg++)
        opt.lagged.emplace_back(arg[iarg]);
    } else if (key == "precond") {
      opt.precond_given = true;
      opt.precond = (PrecondKind) choose(kPrecondWords);
      if (iarg < narg && strcmp(arg[iarg], "petsc") == 0) {
        if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm precond amg petsc", error);
        if (opt.precond != PrecondKind::amg)
          error->all(FLERR, "Illegal fix sissm command: petsc options need precond amg");
        opt.petsc = arg[iarg + 1];
        iarg += 2;
      }
    } else if (key == "unconverged") {
      opt.retry.unconverged = (Unconverged) choose(kUnconvergedWords);
      if (opt.retry.unconverged == Unconverged::cutback && iarg < narg && isdigit(arg[iarg][0])) {
        value = arg[iarg++];
        opt.retry.max_cutback = utils::inumeric(FLERR, value, false, lmp);
      }
    } else if (key == "scheme") {
      opt.scheme = kSchemeWords[choose(kSchemeWords)];
      if (opt.scheme == "genalpha" && iarg < narg &&
          (isdigit(arg[iarg][0]) || arg[iarg][0] == '.' || arg[iarg][0] == '-')) {
        value = arg[iarg++];
        opt.rho_inf = utils::numeric(FLERR, value, false, lmp);
      }
    }
    const std::string bad = value_problem(opt, key);
    if (!bad.empty()) error->all(FLERR, "Illegal fix sissm command: {}, got {}", bad, value);
  }
  const std::string refused = settle(opt);
  if (!refused.empty()) error->all(FLERR, "Illegal fix sissm command: {}", refused);

  scheme = PeriSISSM::make_time_scheme(opt.scheme, opt.rho_inf);
  ncols = scheme->history_columns();
  if (ncols > 0) {
    // the history travels with the atoms and is kept in restart files
    restart_global = 1;
    restart_peratom = 1;
    maxexchange = ncols;
    grow_arrays(atom->nmax);
    atom->add_callback(Atom::GROW);
    atom->add_callback(Atom::RESTART);
    for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
  }
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
  if (ncols > 0) {
    atom->delete_callback(id, Atom::GROW);
    atom->delete_callback(id, Atom::RESTART);
  }
  memory->destroy(hist);
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
  // membranes without bending: the coarse level's matrix has no stiffness out of their plane
  // but the mass (with bending, the hinges give it one), and amg lets such a flat membrane
  // leave its plane (measured: the hanging strip of examples/membranes buckles sideways in the
  // first step and then misses the tolerance; block keeps it in its plane), so the default is
  // block there
  if (!opt.precond_given && opt.precond == PrecondKind::amg && forces->has_unbent_membranes()) {
    opt.precond = PrecondKind::block;
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "Fix sissm {}: membranes without bending (pair_coeff ... membrane yes, no "
                     "bend): precond block (the default amg has no out-of-plane stiffness for "
                     "them; precond amg asks for it)\n",
                     id);
  }
  block_precond = std::make_unique<PeriSISSM::BlockPreconditioner>();
  amg_precond.reset();
  if (opt.precond == PrecondKind::amg) amg_precond = make_amg();
  precond = amg_precond ? amg_precond.get() : block_precond.get();
  // the options of this run decide which work arrays exist: allocate them anew
  destroy_arrays();
  nmax = 0;
}

/* ----------------------------------------------------------------------
   collision-free steps (collision_limit.h): the positions at the start of a (sub-)step are
   admissible; every later move of the group is limited so that no contact pair comes within
   its thickness on the straight move from the last admissible positions. The contacts'
   lagged friction is taken there too (begin_step, h the (sub-)step), and the stiffness of
   those that adapt it is balanced at the first evaluation of the step (balance_first)
------------------------------------------------------------------------- */

void FixSissm::begin_path(double h)
{
  comm->forward_comm();
  for (CollisionLimit *contact : contacts) contact->begin_step(h, scheme->force_factor());
  balance_first = !adapting.empty();
  for (CollisionLimit *limit : limiters) limit->begin_path();
}

// ghost positions current on entry and on return
void FixSissm::limit_path(bool end_of_step)
{
  reach_cut = 0;
  for (CollisionLimit *limit : limiters) {
    if (limit->limit_move(groupbit) < 1.0) comm->forward_comm();
    if (limit->reach_limited()) {
      if (end_of_step) limit->reach_error("fix sissm");
      reach_cut = 1;
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
          {nullptr, &gnode, 1, opt.precond == PrecondKind::amg, "sissm:gnode"},
          {&rprev, nullptr, 3, opt.relax, "sissm:rprev"},
          {&dprev, nullptr, 3, opt.relax, "sissm:dprev"},
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

/* ---------------------------------------------------------------------- */

void FixSissm::setup(int /*vflag*/)
{
  last_iterations = 0;
  last_measure = 0.0;
  last_substeps = 1;
  last_newton = last_krylov = 0;
  nsteps_run = iterations_run = unconverged_run = cutback_run = fallback_run = 0;
  warned = warned_roundoff = warned_fallback = 0;
  block_first = 0;
}

/* ----------------------------------------------------------------------
   the run's solver statistics in the log (thermo shows them per step: outputs 1-9)
------------------------------------------------------------------------- */

void FixSissm::post_run()
{
  if (comm->me != 0 || nsteps_run == 0) return;
  std::string text = fmt::format("Fix sissm {} run: {} steps, {:.6g} iterations per step, {} "
                                 "unconverged, {} cut back, {} preconditioner switches",
                                 id, nsteps_run, (double) iterations_run / nsteps_run,
                                 unconverged_run, cutback_run, fallback_run);
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
    const PeriSISSM::KrylovWork work{xbase, rbase, jbase, cres, zdir, pdir, sdir, term};
    result = PeriSISSM::solve_newton_krylov(*system, *precond, opt.iterations, work);
    // (tolerance 0: every step runs to the limit by request, which says nothing of the
    // preconditioner)
    precond->finished(result.newton, result.krylov, result.converged() || opt.tolerance == 0.0);
  } else {
    result = PeriSISSM::solve_jacobi(*system, opt.iterations, {rprev, dprev});
  }
  last_newton += result.newton;
  last_krylov += result.krylov;
  if (!forces->group_coupled(groupbit)) {
    const PeriSISSM::MomentumBalance balance{h, scheme->force_factor(), scheme->name() == "euler"};
    PeriSISSM::balance_momentum(rows, *reductions, balance, x, yn, yhat, flag ? nullptr : fext,
                                moment);
  }
  // the last move (the final correction, the momentum balance) is limited like the others
  if (!limiters.empty()) {
    comm->forward_comm();
    limit_path(true);
  }
  scheme->finish(rows, arrays);
  if (move_others) place_others(t_end);
  return result;
}

/* ----------------------------------------------------------------------
   the step as the retry ladder drives it (solvers/step_retry.h). A redone step starts again
   from y^n, v^n (kept in xstart, vstart). Cut back into n sub-steps, atoms outside the group
   (held, or moved by fix move or another integrator, already at t^{n+1}) sit at
   x^{n+1} - (1 - t) h v at the end t (a fraction of the step) of each sub-step, and at x^{n+1}
   afterwards; the other fixes' forces are those of t^{n+1} throughout.
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class SissmAttempts : public PeriSISSM::StepAttempts {
 public:
  SissmAttempts(FixSissm *fix, double **flag) : fix_(fix), flag_(flag) {}
  PeriSISSM::SolveResult solve(int n, int s) override
  {
    return fix_->solve_step(fix_->dtv / n, (double) (s + 1) / n, flag_);
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
  const PeriSISSM::SolveResult &result = outcome.result;
  if (outcome.switched) {
    if (outcome.switch_converged) block_first = precond == block_precond.get();
    fallback_run++;
    if (!warned_fallback && comm->me == 0)
      error->warning(FLERR,
                     "Fix sissm {}: step {} did not converge with precond {}; redone with the {} "
                     "preconditioner ({}; the one that converged goes first from now on; "
                     "counted in f_{}[9]; reported once per run)",
                     id, update->ntimestep, precond == block_precond.get() ? "amg" : "block",
                     precond == block_precond.get() ? "block" : "amg",
                     outcome.switch_converged ? "converged" : "not converged either", id);
    warned_fallback = 1;
  }
  if (!outcome.cut_back) return;
  const int substeps = outcome.substeps;
  if (outcome.cutback_failed)
    error->all(FLERR,
               "Fix sissm {}: step {} did not converge in {} iterations per step, not even as {} "
               "sub-steps of {:.6g} (convergence measure {:.3g} > tolerance {:.3g}): raise "
               "iterations, lower the time step, or accept unconverged steps with 'unconverged "
               "warn'",
               id, update->ntimestep, opt.iterations, substeps, dtv / substeps, result.measure,
               result.tolerance);
  cutback_run++;
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "Fix sissm {}: step {} did not converge in {} iterations; redone as {} "
                   "sub-steps of {:.6g} (counted in f_{}[6])\n",
                   id, update->ntimestep, opt.iterations, substeps, dtv / substeps, id);
}

/* ----------------------------------------------------------------------
   the atoms outside the group (held, or moved by fix move or another integrator, already at
   t^{n+1}) at the fraction t of the step: x^{n+1} - (1 - t) h v
------------------------------------------------------------------------- */

void FixSissm::place_others(double t)
{
  double **x = atom->x;
  double **v = atom->v;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (!(mask[i] & groupbit))
      for (int k = 0; k < 3; k++) x[i][k] = xstart[i][k] - (1.0 - t) * dtv * v[i][k];
}

/* ----------------------------------------------------------------------
   the group back at y^n, v^n and the scheme's history of the start of the step (kept in
   xstart, vstart, hstart, state_start)
------------------------------------------------------------------------- */

void FixSissm::restore_start()
{
  double **x = atom->x;
  double **v = atom->v;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) {
      for (int k = 0; k < 3; k++) {
        x[i][k] = xstart[i][k];
        v[i][k] = vstart[i][k];
      }
      for (int k = 0; k < ncols; k++) hist[i][k] = hstart[i][k];
    }
  if (!state_start.empty()) scheme->set_state(state_start.data());
}

/* ---------------------------------------------------------------------- */

void FixSissm::post_integrate()
{
  grow();
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const bool lagged = external_mode == PeriSISSM::ExternalMode::lagged;
  const bool mixed = external_mode == PeriSISSM::ExternalMode::mixed;
  PeriSISSM::Rows &rows = system->step_rows();
  rows.n = nlocal;
  rows.mask = mask;
  rows.bit = groupbit;
  rows.volume = atom->vfrac;
  rows.density = atom->rmass;
  // the particle sizes of the convergence measure, once per step rather than per iteration
  for (int i = 0; i < nlocal; i++) psize[i] = cbrt(atom->vfrac[i]);
  rows.size = psize;

  // lagged: fint of ghosts belongs to their owners (short-range contact with newton on)
  if ((lagged || mixed) && force->newton_pair) comm->reverse_comm(this);
  if (mixed) lagged_external_force();
  if (lagged)
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < 3; k++) flagged[i][k] = (mask[i] & groupbit) ? f[i][k] - fint[i][k] : 0.0;
  if (xstart)
    for (int i = 0; i < nlocal; i++) {
      for (int k = 0; k < 3; k++) {
        xstart[i][k] = x[i][k];
        vstart[i][k] = v[i][k];
      }
      for (int k = 0; k < ncols; k++) hstart[i][k] = hist[i][k];
    }
  if (ncols > 0) {
    // the force density at y^n starts the history of atoms that have none; an atom outside
    // the group has none when it joins
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) fstart[i][k] = f[i][k];
      else
        hist[i][ncols - 1] = 0.0;
    state_start.resize(scheme->state_size());
    if (!state_start.empty()) scheme->get_state(state_start.data());
  }

  last_newton = last_krylov = 0;
  // tolerance 0 asks for every step to use all its iterations: such a step is neither redone
  // nor refused
  opt.retry.fixed_count = opt.tolerance == 0.0;
  opt.retry.two_preconditioners = amg_precond != nullptr;
  PeriSISSM::RetryOutcome outcome;
  {
    ImplicitStep step(forces, groupbit);
    // precond amg: the preconditioner that converged the last step goes first
    precond = (amg_precond && !block_first) ? amg_precond.get() : block_precond.get();
    SissmAttempts attempts(this, lagged ? flagged : nullptr);
    outcome = PeriSISSM::run_retry_ladder(attempts, opt.retry);
    report_retries(outcome);
  }
  const PeriSISSM::SolveResult &result = outcome.result;
  const double measure = result.measure;

  // the blow-up guard of pair peri/nosb, now that the atoms are at y^{n+1} (before LAMMPS
  // decides on a neighbor list build): a diverged step ends in an error, not in LAMMPS's
  // neighbor binning
  forces->check_motion(measure <= tol_step ? 1 : 0);
  // short-range contact: a result beyond what the candidates could follow is refused, and
  // the next step starts from a fresh neighbor list if this one moved atoms far
  const std::string cause = (measure > tol_step)
      ? fmt::format("this step stopped at the iteration limit with convergence measure {:.3g} "
                    "above the tolerance {:.3g}, so the motion may be an artefact of the "
                    "unconverged solve",
                    measure, tol_step)
      : "";
  bool rebuild = forces->contact_end_of_step(cause);
  for (CollisionLimit *limit : limiters) rebuild = limit->rebuild_wanted() || rebuild;
  if (rebuild) next_reneighbor = update->ntimestep;

  const int evaluations = outcome.evaluations;
  last_iterations = evaluations;
  last_measure = measure;
  last_substeps = outcome.substeps;
  nsteps_run++;
  iterations_run += evaluations;
  const PeriSISSM::StepVerdict verdict = PeriSISSM::step_verdict(opt.retry, measure, tol_step);
  if (verdict != PeriSISSM::StepVerdict::converged) {
    unconverged_run++;
    if (verdict == PeriSISSM::StepVerdict::error)
      error->all(FLERR,
                 "Fix sissm {}: step {} stopped at {} iterations with convergence measure {:.3g} "
                 "> tolerance {:.3g} (unconverged error)",
                 id, update->ntimestep, evaluations, measure, tol_step);
    if (!warned && comm->me == 0)
      error->warning(FLERR,
                     "Fix sissm: step {} stopped at {} iterations with convergence measure {:.3g} "
                     "> tolerance {:.3g} (counted in f_{}[4]; reported once per run)",
                     update->ntimestep, evaluations, measure, opt.tolerance, id);
    warned = 1;
  }
}

/* ---------------------------------------------------------------------- */

double FixSissm::compute_vector(int n)
{
  if (n == 0) return last_iterations;
  if (n == 1) return last_measure;
  if (n == 2) return nsteps_run ? (double) iterations_run / nsteps_run : 0.0;
  if (n == 3) return (double) unconverged_run;
  if (n == 4) return last_substeps;
  if (n == 5) return (double) cutback_run;
  if (n == 6) return last_krylov;
  if (n == 7) return last_newton;
  return (double) fallback_run;
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
