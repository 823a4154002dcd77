/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm (doc/theory.rst, "The implicit step"). Per step, with h the time step, for the atoms of the group,
   the backward-Euler problem
     r_i(y) = rho_i (yhat_i - y_i) + h^2 f_i(y) = 0,     yhat_i = y_i^n + h v_i^n
   where f is the exact peri/nosb force density plus, with external implicit (default), the
   forces of the other fixes re-evaluated at y (external lagged: they are taken at y^n, from
   the total force of the last evaluation minus the pair part captured in pre_reverse, and
   moved into yhat as h^2 fext / rho). So a converged step is the backward-Euler step of the
   material fix nve integrates. The per-particle implicit block
     D_i = rho_i I + h^2 sum_j omega_ij (H_i + H_j + (C_i + C_j)/2 I)
   drives two solvers:
     jacobi   y^{k+1} = y^k + alpha_i D_i^-1 r_i(y^k)               (the SISSM sweep)
     krylov   Newton steps J s = r, J = -dr/dy, solved by conjugate gradients preconditioned
              with D (products J p by a finite difference of r along p), with a backtracking
              safeguard on sum_i V_i |r_i|^2 / rho_i
   both started at y^0 = y^n + h v^n (an equilibrium is a fixed point for any iteration
   count); an "iteration" is one force evaluation. End of step: v^{n+1} = (y^{n+1} - y^n) / h.
   The solve runs in post_integrate, after every initial_integrate, so particles prescribed by
   fix move or other integrators already sit at t^{n+1}. Keyword scheme replaces backward Euler
   by BDF2 or generalized-alpha (src/core/solvers/time_scheme.h): the same problem with another
   predictor yhat and factor c in place of h^2, and a per-atom history (fix_sissm_history.cpp).
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
#include <initializer_list>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

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

bool is_keyword(const char *word)
{
  for (const char *k : {"iterations", "tolerance", "relax", "solver", "external", "lagged",
                        "precond", "unconverged", "scheme"})
    if (strcmp(word, k) == 0) return true;
  return false;
}

}    // namespace

/* ---------------------------------------------------------------------- */

FixSissm::FixSissm(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), forces(nullptr), solver(KRYLOV),
    precond_type(kDefaultAmg ? PRECOND_AMG : PRECOND_BLOCK), precond_given(0), maxiter(100),
    tolerance(1.0e-6), relax(0), implicit_external(1), external_mode(PeriSISSM::ExternalMode::none),
    dtv(0.0), tol_step(1.0e-6), last_iterations(0), last_measure(0.0), nsteps_run(0),
    iterations_run(0), unconverged_run(0), last_substeps(1), last_newton(0), last_krylov(0),
    cutback_run(0), fallback_run(0), warned_fallback(0), block_first(0), warned(0),
    warned_roundoff(0), nmax(0), fint(nullptr), fext(nullptr), flagged(nullptr), yn(nullptr),
    yhat(nullptr), res(nullptr), kblock(nullptr), rprev(nullptr), dprev(nullptr), xbase(nullptr),
    rbase(nullptr), jbase(nullptr), cres(nullptr), zdir(nullptr), pdir(nullptr), sdir(nullptr),
    term(nullptr), moment(nullptr), xstart(nullptr), vstart(nullptr), hstart(nullptr), vn(nullptr),
    fstart(nullptr), gnode(nullptr), psize(nullptr)
{
  ncols = 0;
  hist = nullptr;
  hist_from_restart = 1;
  reductions = std::make_unique<WorldReductions>(lmp, world);
  system = std::make_unique<SissmSystem>(this, *reductions);
  std::string scheme_name = "euler";
  double rho_inf = 0.8;
  time_integrate = 1;
  force_reneighbor = 1;    // after steps that moved atoms far (short-range contact)
  next_reneighbor = -1;
  vector_flag = 1;
  size_vector = 9;
  comm_forward = 1;    // amg: global node numbers of the ghosts
  global_freq = 1;
  extvector = 0;

  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "iterations") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm iterations", error);
      maxiter = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxiter < 1)
        error->all(FLERR, "Illegal fix sissm command: iterations must be >= 1, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "tolerance") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm tolerance", error);
      tolerance = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(tolerance >= 0.0))
        error->all(FLERR, "Illegal fix sissm command: tolerance must be >= 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "relax") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm relax", error);
      relax = utils::logical(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (strcmp(arg[iarg], "solver") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm solver", error);
      if (strcmp(arg[iarg + 1], "jacobi") == 0)
        solver = JACOBI;
      else if (strcmp(arg[iarg + 1], "krylov") == 0)
        solver = KRYLOV;
      else
        error->all(FLERR, "Illegal fix sissm command: solver must be jacobi or krylov, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "external") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm external", error);
      if (strcmp(arg[iarg + 1], "implicit") == 0)
        implicit_external = 1;
      else if (strcmp(arg[iarg + 1], "lagged") == 0)
        implicit_external = 0;
      else
        error->all(FLERR,
                   "Illegal fix sissm command: external must be implicit or lagged, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "lagged") == 0) {
      // the fix IDs up to the next keyword
      if (iarg + 2 > narg || is_keyword(arg[iarg + 1]))
        utils::missing_cmd_args(FLERR, "fix sissm lagged", error);
      for (iarg++; iarg < narg && !is_keyword(arg[iarg]); iarg++)
        lagged_ids.emplace_back(arg[iarg]);
    } else if (strcmp(arg[iarg], "precond") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm precond", error);
      precond_given = 1;
      if (strcmp(arg[iarg + 1], "block") == 0)
        precond_type = PRECOND_BLOCK;
      else if (strcmp(arg[iarg + 1], "amg") == 0)
        precond_type = PRECOND_AMG;
      else
        error->all(FLERR, "Illegal fix sissm command: precond must be block or amg, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
      if (iarg < narg && strcmp(arg[iarg], "petsc") == 0) {
        if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm precond amg petsc", error);
        if (precond_type != PRECOND_AMG)
          error->all(FLERR, "Illegal fix sissm command: petsc options need precond amg");
        petsc_options = arg[iarg + 1];
        iarg += 2;
      }
    } else if (strcmp(arg[iarg], "unconverged") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm unconverged", error);
      using PeriSISSM::Unconverged;
      if (strcmp(arg[iarg + 1], "warn") == 0)
        retry.unconverged = Unconverged::warn;
      else if (strcmp(arg[iarg + 1], "error") == 0)
        retry.unconverged = Unconverged::error;
      else if (strcmp(arg[iarg + 1], "cutback") == 0)
        retry.unconverged = Unconverged::cutback;
      else
        error->all(FLERR,
                   "Illegal fix sissm command: unconverged must be warn, error or cutback, "
                   "got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
      if (retry.unconverged == Unconverged::cutback && iarg < narg && isdigit(arg[iarg][0])) {
        retry.max_cutback = utils::inumeric(FLERR, arg[iarg], false, lmp);
        if (retry.max_cutback < 1 || retry.max_cutback > 20)
          error->all(FLERR,
                     "Illegal fix sissm command: unconverged cutback levels must be 1 to 20, "
                     "got {}",
                     arg[iarg]);
        iarg++;
      }
    } else if (strcmp(arg[iarg], "scheme") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm scheme", error);
      scheme_name = arg[iarg + 1];
      if (scheme_name != "euler" && scheme_name != "bdf2" && scheme_name != "genalpha")
        error->all(FLERR,
                   "Illegal fix sissm command: scheme must be euler, bdf2 or genalpha, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
      if (scheme_name == "genalpha" && iarg < narg &&
          (isdigit(arg[iarg][0]) || arg[iarg][0] == '.' || arg[iarg][0] == '-')) {
        rho_inf = utils::numeric(FLERR, arg[iarg], false, lmp);
        if (!(rho_inf >= 0.0 && rho_inf <= 1.0))
          error->all(FLERR,
                     "Illegal fix sissm command: scheme genalpha rho_inf must be 0 to 1, got {}",
                     arg[iarg]);
        iarg++;
      }
    } else {
      error->all(FLERR,
                 "Illegal fix sissm command: unknown keyword '{}' (allowed: iterations, "
                 "tolerance, solver, precond, unconverged, scheme, relax, external, lagged)",
                 arg[iarg]);
    }
  }
  if (relax && solver != JACOBI)
    error->all(FLERR, "Illegal fix sissm command: relax yes requires solver jacobi");
  if (solver == JACOBI && precond_given && precond_type == PRECOND_AMG)
    error->all(FLERR,
               "Illegal fix sissm command: precond amg needs solver krylov (the jacobi "
               "sweeps use the blocks themselves)");
  if (solver == JACOBI) precond_type = PRECOND_BLOCK;

  scheme = PeriSISSM::make_time_scheme(scheme_name, rho_inf);
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
  if (precond_type == PRECOND_AMG)
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
  if (!precond_given && precond_type == PRECOND_AMG && forces->has_unbent_membranes()) {
    precond_type = PRECOND_BLOCK;
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "Fix sissm {}: membranes without bending (pair_coeff ... membrane yes, no "
                     "bend): precond block (the default amg has no out-of-plane stiffness for "
                     "them; precond amg asks for it)\n",
                     id);
  }
  block_precond = std::make_unique<PeriSISSM::BlockPreconditioner>();
  amg_precond.reset();
  if (precond_type == PRECOND_AMG) amg_precond = make_amg();
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
   per-atom work arrays: only those the chosen options use
------------------------------------------------------------------------- */

void FixSissm::destroy_arrays()
{
  for (double ***a :
       {&fint,  &fext, &flagged, &yn,   &yhat, &res,    &kblock, &rprev,  &dprev,  &xbase, &rbase,
        &jbase, &cres, &zdir,    &pdir, &sdir, &moment, &xstart, &vstart, &hstart, &vn,    &fstart})
    memory->destroy(*a);
  memory->destroy(term);
  memory->destroy(gnode);
  memory->destroy(psize);
}

void FixSissm::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  const bool lagged = external_mode == PeriSISSM::ExternalMode::lagged ||
      external_mode == PeriSISSM::ExternalMode::mixed;
  const bool restart_step = retry.unconverged == PeriSISSM::Unconverged::cutback ||
      precond_type == PRECOND_AMG || scheme->force_time() < 1.0;
  memory->grow(kblock, nmax, 6, "sissm:block");
  memory->grow(psize, nmax, "sissm:size");
  memory->grow(yn, nmax, 3, "sissm:yn");
  memory->grow(yhat, nmax, 3, "sissm:yhat");
  memory->grow(res, nmax, 3, "sissm:res");
  memory->grow(fext, nmax, 3, "sissm:fext");
  memory->grow(moment, nmax, PeriSISSM::kMomentumColumns, "sissm:moment");
  if (lagged) {
    memory->grow(fint, nmax, 3, "sissm:fint");
    memory->grow(flagged, nmax, 3, "sissm:flagged");
  }
  if (restart_step) {
    memory->grow(xstart, nmax, 3, "sissm:xstart");
    memory->grow(vstart, nmax, 3, "sissm:vstart");
    if (ncols > 0) memory->grow(hstart, nmax, ncols, "sissm:hstart");
  }
  if (ncols > 0) {
    memory->grow(vn, nmax, 3, "sissm:vn");
    memory->grow(fstart, nmax, 3, "sissm:fstart");
  }
  if (precond_type == PRECOND_AMG) memory->grow(gnode, nmax, "sissm:gnode");
  if (relax) {
    memory->grow(rprev, nmax, 3, "sissm:rprev");
    memory->grow(dprev, nmax, 3, "sissm:dprev");
  }
  if (solver == KRYLOV) {
    for (double ***a : {&xbase, &rbase, &jbase, &cres, &zdir, &pdir, &sdir})
      memory->grow(*a, nmax, 3, "sissm:krylov");
    memory->grow(term, nmax, "sissm:term");
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
  arrays.y = x;
  arrays.v = v;
  arrays.yn = yn;
  arrays.vn = vn;
  arrays.yhat = yhat;
  arrays.hist = hist;
  arrays.flag = flag;
  arrays.fstart = fstart;
  const PeriSISSM::Rows &rows = system->rows();
  scheme->begin(rows, arrays);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) fext[i][0] = fext[i][1] = fext[i][2] = 0.0;

  system->begin_solve();
  PeriSISSM::SolveResult result;
  if (solver == KRYLOV) {
    PeriSISSM::KrylovWork work;
    work.xbase = xbase;
    work.rbase = rbase;
    work.jbase = jbase;
    work.cres = cres;
    work.zdir = zdir;
    work.pdir = pdir;
    work.sdir = sdir;
    work.term = term;
    result = PeriSISSM::solve_newton_krylov(*system, *precond, maxiter, work);
  } else {
    PeriSISSM::SweepMemory memory_rows;
    memory_rows.rprev = rprev;
    memory_rows.dprev = dprev;
    result = PeriSISSM::solve_jacobi(*system, maxiter, memory_rows);
  }
  // (tolerance 0: every step runs to the limit by request, which says nothing of the
  // preconditioner)
  if (solver == KRYLOV)
    precond->finished(result.newton, result.krylov, result.converged() || tolerance == 0.0);
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
               id, update->ntimestep, maxiter, substeps, dtv / substeps, result.measure,
               result.tolerance);
  cutback_run++;
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "Fix sissm {}: step {} did not converge in {} iterations; redone as {} "
                   "sub-steps of {:.6g} (counted in f_{}[6])\n",
                   id, update->ntimestep, maxiter, substeps, dtv / substeps, id);
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
  retry.fixed_count = tolerance == 0.0;
  retry.two_preconditioners = amg_precond != nullptr;
  PeriSISSM::RetryOutcome outcome;
  {
    ImplicitStep step(forces, groupbit);
    // precond amg: the preconditioner that converged the last step goes first
    precond = (amg_precond && !block_first) ? amg_precond.get() : block_precond.get();
    SissmAttempts attempts(this, lagged ? flagged : nullptr);
    outcome = PeriSISSM::run_retry_ladder(attempts, retry);
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
  const PeriSISSM::StepVerdict verdict = PeriSISSM::step_verdict(retry, measure, tol_step);
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
                     update->ntimestep, evaluations, measure, tolerance, id);
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
  // the per-atom arrays grow() allocates (PETSc's matrix and hierarchy are not counted)
  // yn, yhat, res, fext, block, moment, size
  int arrays = 4 * 3 + 6 + PeriSISSM::kMomentumColumns + 1;
  if (fint) arrays += 2 * 3;                             // fint, flagged
  if (xstart) arrays += 2 * 3 + (hstart ? ncols : 0);    // redone steps
  arrays += ncols + (vn ? 2 * 3 : 0);                    // the scheme's history, v^n and f at y^n
  if (gnode) arrays += 1;
  if (relax) arrays += 6;
  if (solver == KRYLOV) arrays += 7 * 3 + 1;
  return (double) arrays * nmax * sizeof(double);
}
