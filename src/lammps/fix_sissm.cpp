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

#include "implicit_forces.h"

#include "linalg/exact_sum.h"
#include "solvers/jacobi.h"
#include "solvers/momentum.h"
#include "solvers/newton_krylov.h"
#include "solvers/preconditioner.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
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

}    // namespace

/* ---------------------------------------------------------------------- */

FixSissm::FixSissm(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), forces(nullptr), solver(KRYLOV),
    precond_type(kDefaultAmg ? PRECOND_AMG : PRECOND_BLOCK), maxiter(100), tolerance(1.0e-6),
    relax(0), implicit_external(1), external_mode(EXT_NONE),
    precond_given(0), unconverged(UNCONVERGED_CUTBACK), max_cutback(4), dtv(0.0),
    tol_step(1.0e-6),
    last_iterations(0), last_measure(0.0), nsteps_run(0), iterations_run(0), unconverged_run(0),
    last_substeps(1), last_newton(0), last_krylov(0), cutback_run(0), fallback_run(0),
    warned_fallback(0), block_first(0), warned(0), warned_roundoff(0), nmax(0), evaluations_(0),
    contact_incomplete(0), reach_cut(0), fint(nullptr),
    fext(nullptr), flagged(nullptr),
    yn(nullptr), yhat(nullptr), res(nullptr), kblock(nullptr), rprev(nullptr), dprev(nullptr),
    xbase(nullptr), rbase(nullptr), jbase(nullptr), cres(nullptr), zdir(nullptr), pdir(nullptr),
    sdir(nullptr), term(nullptr), moment(nullptr), xstart(nullptr), vstart(nullptr),
    hstart(nullptr), vn(nullptr), fstart(nullptr), gnode(nullptr), psize(nullptr)
{
  ncols = 0;
  hist = nullptr;
  hist_from_restart = 1;
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
      if (strcmp(arg[iarg + 1], "jacobi") == 0) solver = JACOBI;
      else if (strcmp(arg[iarg + 1], "krylov") == 0) solver = KRYLOV;
      else
        error->all(FLERR, "Illegal fix sissm command: solver must be jacobi or krylov, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "external") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm external", error);
      if (strcmp(arg[iarg + 1], "implicit") == 0) implicit_external = 1;
      else if (strcmp(arg[iarg + 1], "lagged") == 0) implicit_external = 0;
      else
        error->all(FLERR,
                   "Illegal fix sissm command: external must be implicit or lagged, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "precond") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sissm precond", error);
      precond_given = 1;
      if (strcmp(arg[iarg + 1], "block") == 0) precond_type = PRECOND_BLOCK;
      else if (strcmp(arg[iarg + 1], "amg") == 0) precond_type = PRECOND_AMG;
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
      if (strcmp(arg[iarg + 1], "warn") == 0) unconverged = UNCONVERGED_WARN;
      else if (strcmp(arg[iarg + 1], "error") == 0) unconverged = UNCONVERGED_ERROR;
      else if (strcmp(arg[iarg + 1], "cutback") == 0) unconverged = UNCONVERGED_CUTBACK;
      else
        error->all(FLERR,
                   "Illegal fix sissm command: unconverged must be warn, error or cutback, "
                   "got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
      if (unconverged == UNCONVERGED_CUTBACK && iarg < narg && isdigit(arg[iarg][0])) {
        max_cutback = utils::inumeric(FLERR, arg[iarg], false, lmp);
        if (max_cutback < 1 || max_cutback > 20)
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
                 "tolerance, solver, precond, unconverged, scheme, relax, external)",
                 arg[iarg]);
    }
  }
  if (relax && solver != JACOBI)
    error->all(FLERR, "Illegal fix sissm command: relax yes requires solver jacobi");
  if (solver == JACOBI && precond_given && precond_type == PRECOND_AMG)
    error->all(FLERR, "Illegal fix sissm command: precond amg needs solver krylov (the jacobi "
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
   the forces of the other fixes (those that add forces after the pair style, in post_force).
   Re-evaluating a fix at every iterate is right only for a fix whose force is a pure function
   of the positions, velocities and forces at that moment: the known ones are listed below.
   A fix with state or random numbers (langevin, smd, python/invoke, external, a dynamic
   group, unknown styles) must run exactly once per step: its force is lagged, taken from the
   evaluation that ended the previous step. When the pure ones all add a force that does not
   depend on the force so far, the two kinds mix (MIXED); a pure fix that rewrites the force
   (setforce, aveforce, lineforce, planeforce) next to a lagged one leaves only the fully
   lagged treatment. What is decided is written to the log when it changes.
------------------------------------------------------------------------- */

namespace {
bool is_pure_additive(const std::string &style)
{
  static const char *const names[] = {
      "gravity",    "addforce",     "viscous",     "indent",     "wall/lj93",   "wall/lj126",
      "wall/lj1043", "wall/colloid", "wall/harmonic", "wall/morse", "wall/table", "wall/region",
      "spring",     "spring/self",  "drag",        "efield",     "nosb/contact"};
  for (const char *n : names)
    if (style == n) return true;
  return false;
}

bool is_pure_rewriting(const std::string &style)
{
  return style == "setforce" || style == "aveforce" || style == "lineforce" ||
      style == "planeforce";
}
}    // namespace

void FixSissm::choose_external()
{
  implicit_fixes.clear();
  std::vector<Fix *> lagged;
  int rewriting = 0;
  const auto &fixes = modify->get_fix_list();
  // Modify::post_force calls the dynamic-group fixes (style GROUP) first, then the others
  for (int pass = 0; pass < 2; pass++) {
    for (Fix *f : fixes) {
      if (f == this || !(modify->get_fix_mask(f) & POST_FORCE)) continue;
      if ((strcmp(f->style, "GROUP") == 0) != (pass == 0)) continue;
      const std::string style(f->style);
      if (is_pure_additive(style)) implicit_fixes.push_back(f);
      else if (is_pure_rewriting(style)) {
        implicit_fixes.push_back(f);
        rewriting = 1;
      } else
        lagged.push_back(f);
    }
  }

  std::string note;
  if (implicit_fixes.empty() && lagged.empty()) external_mode = EXT_NONE;
  else if (!implicit_external) external_mode = EXT_LAGGED;
  else if (lagged.empty()) external_mode = EXT_IMPLICIT;
  else {
    std::string names;
    for (Fix *f : lagged) names += fmt::format("{}{} ({})", names.empty() ? "" : ", ", f->id,
                                                f->style);
    if (rewriting) {
      external_mode = EXT_LAGGED;
      note = fmt::format("Fix sissm {}: fix {} may hold state or random numbers and must act once "
                         "per step, and a fix that rewrites forces (setforce, aveforce, lineforce, "
                         "planeforce) is present: the forces of all other fixes are lagged (taken "
                         "at the start of each step, as with 'external lagged')\n",
                         id, names);
    } else {
      external_mode = EXT_MIXED;
      note = fmt::format("Fix sissm {}: fix {} may hold state or random numbers and must act once "
                         "per step: its force is lagged (taken at the start of each step); the "
                         "other fixes' forces are implicit\n",
                         id, names);
    }
  }
  if (note != external_note && comm->me == 0 && !note.empty()) utils::logmesg(lmp, note);
  external_note = note;

  // contact that limits the moves (collision-free steps) must be part of every iterate
  limiters.clear();
  contacts.clear();
  adapting.clear();
  for (Fix *f : fixes) {
    auto *limit = dynamic_cast<CollisionLimit *>(f);
    if (!limit) continue;
    const bool implicit = external_mode != EXT_LAGGED &&
        std::find(implicit_fixes.begin(), implicit_fixes.end(), f) != implicit_fixes.end();
    // its lagged friction is built at the start of each (sub-)step when it is an iterate's force
    if (implicit) contacts.push_back(limit);
    // a contact that needs every iterate's force, while the other fixes' forces are lagged
    auto refuse_lagged = [&](const char *needs, const char *remedy) {
      error->all(FLERR,
                 "Fix sissm {}: fix {} ({}) {}, so its force must be re-evaluated at every "
                 "iterate, but the forces of the other fixes are lagged here ({}): remove that, "
                 "or {}",
                 id, f->id, f->style, needs,
                 implicit_external ? "a fix that rewrites forces is present; hold atoms by "
                                     "leaving them out of fix sissm's group instead"
                                   : "keyword external lagged",
                 remedy);
    };
    if (limit->adapts_stiffness()) {
      if (!implicit)
        refuse_lagged("adapts its stiffness to the implicit step (kappa auto)",
                      "give kappa as a number");
      adapting.push_back(limit);
    }
    if (!limit->limits_moves()) continue;
    if (!implicit)
      refuse_lagged("makes the implicit step collision-free",
                    "turn the collision check off (ccd no)");
    limiters.push_back(limit);
  }
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
  for (double ***a : {&fint, &fext, &flagged, &yn, &yhat, &res, &kblock, &rprev, &dprev, &xbase,
                      &rbase, &jbase, &cres, &zdir, &pdir, &sdir, &moment, &xstart, &vstart,
                      &hstart, &vn, &fstart})
    memory->destroy(*a);
  memory->destroy(term);
  memory->destroy(gnode);
  memory->destroy(psize);
}

void FixSissm::grow()
{
  if (atom->nmax <= nmax) return;
  destroy_arrays();
  nmax = atom->nmax;
  memory->create(kblock, nmax, 6, "sissm:block");
  memory->create(psize, nmax, "sissm:size");
  memory->create(yn, nmax, 3, "sissm:yn");
  memory->create(yhat, nmax, 3, "sissm:yhat");
  memory->create(res, nmax, 3, "sissm:res");
  memory->create(fext, nmax, 3, "sissm:fext");
  memory->create(moment, nmax, PeriSISSM::kMomentumColumns, "sissm:moment");
  if (external_mode == EXT_LAGGED || external_mode == EXT_MIXED)
    memory->create(fint, nmax, 3, "sissm:fint");
  if (external_mode == EXT_MIXED || external_mode == EXT_LAGGED)
    memory->create(flagged, nmax, 3, "sissm:flagged");
  if (unconverged == UNCONVERGED_CUTBACK || precond_type == PRECOND_AMG ||
      scheme->force_time() < 1.0) {
    memory->create(xstart, nmax, 3, "sissm:xstart");
    memory->create(vstart, nmax, 3, "sissm:vstart");
    if (ncols > 0) memory->create(hstart, nmax, ncols, "sissm:hstart");
  }
  if (ncols > 0) {
    memory->create(vn, nmax, 3, "sissm:vn");
    memory->create(fstart, nmax, 3, "sissm:fstart");
  }
  if (precond_type == PRECOND_AMG) memory->create(gnode, nmax, "sissm:gnode");
  if (relax) {
    memory->create(rprev, nmax, 3, "sissm:rprev");
    memory->create(dprev, nmax, 3, "sissm:dprev");
  }
  if (solver == KRYLOV) {
    for (double ***a : {&xbase, &rbase, &jbase, &cres, &zdir, &pdir, &sdir})
      memory->create(*a, nmax, 3, "sissm:krylov");
    memory->create(term, nmax, "sissm:term");
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
   external lagged: pair peri/nosb has just computed its force density (and nothing else has
   been added yet, other pair-like contributions do not exist with atom_style peri): keep it,
   for owned and ghost atoms, so that fext = f - fint can be formed at the start of the next
   step
------------------------------------------------------------------------- */

void FixSissm::capture_internal_force()
{
  if (external_mode != EXT_LAGGED && external_mode != EXT_MIXED) return;
  grow();
  double **f = atom->f;
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) {
    fint[i][0] = f[i][0];
    fint[i][1] = f[i][1];
    fint[i][2] = f[i][2];
  }
}

void FixSissm::setup_pre_reverse(int, int)
{
  capture_internal_force();
}

void FixSissm::pre_reverse(int, int)
{
  capture_internal_force();
}

/* ---------------------------------------------------------------------- */

int FixSissm::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    buf[m++] = fint[i][0];
    buf[m++] = fint[i][1];
    buf[m++] = fint[i][2];
  }
  return m;
}

void FixSissm::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    fint[j][0] += buf[m++];
    fint[j][1] += buf[m++];
    fint[j][2] += buf[m++];
  }
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
   one force evaluation at the current positions: ghost positions, the peri/nosb force density
   (without energy/virial; the diagonal blocks only when asked), ghost forces folded back
   (where the pair wrote any), with external implicit the post_force of the other fixes (with
   v the time scheme's velocity of the iterate, so velocity dependent forces such as fix
   viscous are implicit too), then the time scheme's residual r_i = rho_i (yhat_i - y_i) + c f_i
   of the owned atoms of the group into res
------------------------------------------------------------------------- */

void FixSissm::evaluate(bool blocks)
{
  evaluations_++;
  comm->forward_comm();
  if (!limiters.empty()) limit_path(false);
  // an iterate of the solver (a probe of a Jacobian product has no blocks): a contact may
  // change its stiffness here
  if (blocks)
    for (CollisionLimit *contact : adapting) contact->next_iterate();
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double *rho = atom->rmass;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;

  // an iterate that contact candidates could not follow (the pair's short-range contact, or a
  // move cut short by the reach of a contact fix's candidates) cannot count as converged
  contact_incomplete = forces->contact_follow_motion() < 0 || reach_cut;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  forces->evaluate(blocks ? kblock : nullptr);
  if (forces->ghost_forces()) comm->reverse_comm();
  if (external_mode == EXT_IMPLICIT || external_mode == EXT_MIXED) {
    // the other fixes' force at this iterate, kept in fext (f after minus f before)
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        scheme->iterate_velocity(i, arrays, v[i]);
        for (int k = 0; k < 3; k++) fext[i][k] = f[i][k];
      }
    for (Fix *fix : implicit_fixes) fix->post_force(0);
    if (blocks)
      for (CollisionLimit *limit : limiters) limit->add_blocks(kblock);
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) {
          if (external_mode == EXT_MIXED) f[i][k] += flagged[i][k];
          fext[i][k] = f[i][k] - fext[i][k];
        }
  }

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    scheme->residual(rho[i], yhat[i], x[i], f[i], res[i]);
    const double r2 = res[i][0] * res[i][0] + res[i][1] * res[i][1] + res[i][2] * res[i][2];
    if (!std::isfinite(r2))
      error->one(FLERR, "Fix sissm: non-finite position or force of atom {} at step {}",
                 atom->tag[i], update->ntimestep);
  }

  // kappa auto: the barrier's stiffness balanced against the rest of the step's residual at
  // its first evaluation, which is redone when the stiffness changed
  if (balance_first) {
    balance_first = 0;
    bool changed = false;
    for (CollisionLimit *contact : adapting)
      changed = contact->balance_stiffness(res, scheme->force_factor(), groupbit) || changed;
    if (changed) {
      // (the redo's move is empty: a cut of the first move still makes the iterate incomplete)
      const int incomplete = contact_incomplete;
      evaluate(blocks);
      contact_incomplete = contact_incomplete || incomplete;
    }
  }
}

/* ---------------------------------------------------------------------- */

double **FixSissm::unknowns()
{
  return atom->x;
}

/* ----------------------------------------------------------------------
   D_i = rho_i I + h^2 block_i of owned atom i (xx yy zz xy xz yz)
------------------------------------------------------------------------- */

void FixSissm::block(int i, double D[6]) const
{
  scheme->block(atom->rmass[i], kblock[i], D);
}

/* ----------------------------------------------------------------------
   Reductions over the world communicator
------------------------------------------------------------------------- */

void FixSissm::max(double *values, int n)
{
  std::vector<double> all(n);
  MPI_Allreduce(values, all.data(), n, MPI_DOUBLE, MPI_MAX, world);
  for (int k = 0; k < n; k++) values[k] = all[k];
}

void FixSissm::sum(long long *values, int n)
{
  std::vector<long long> all(n);
  MPI_Allreduce(values, all.data(), n, MPI_LONG_LONG, MPI_SUM, world);
  for (int k = 0; k < n; k++) values[k] = all[k];
}

double FixSissm::total_rows() const
{
  return (double) atom->natoms;
}

/* ---------------------------------------------------------------------- */

void FixSissm::check_finite()
{
  double **x = atom->x;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if ((mask[i] & groupbit) && !std::isfinite(x[i][0] + x[i][1] + x[i][2]))
      error->one(FLERR, "Fix sissm: non-finite position of atom {} at step {}", atom->tag[i],
                 update->ntimestep);
}

/* ----------------------------------------------------------------------
   the tolerance this step can meet (asked once, after the first evaluation). Positions are
   absolute coordinates: an atom at |x| from the origin is known to eps |x| (eps the machine
   epsilon), and so are its bond vectors, so the force density of particle i is known to about
   |block_i| eps |x|, and the convergence measure to
     floor_i = eps (|x_i| / l_i) (1 + h^2 |block_i| / rho_i)      (l_i = V_i^(1/3)),
   |x| the largest coordinate, |block| the largest diagonal entry of the SISSM block (the row
   sum of the bond stiffnesses). Measured on a 4x3x3 block at 20 and 100 x the explicit limit
   (neo-Hookean, random velocities), at the origin and moved 4e4 particle sizes away, the
   measure stalls at 0.2 to 0.4 x this estimate (1e-12 at the origin, 2e-8 far away, at
   20 x). A step whose measure is below the larger of the tolerance and half the largest
   estimate counts as converged; the first time in a run that this exceeds the tolerance, a
   warning says so.
   One global max.
------------------------------------------------------------------------- */

double FixSissm::step_tolerance()
{
  double **x = atom->x;
  double *rho = atom->rmass;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double h2 = scheme->force_factor();
  double local[2] = {0.0, 0.0}, all[2];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double xmax = fmax(fabs(x[i][0]), fmax(fabs(x[i][1]), fabs(x[i][2])));
    const double bmax = fmax(kblock[i][0], fmax(kblock[i][1], kblock[i][2]));
    local[0] = fmax(local[0], xmax / psize[i] * (1.0 + h2 * bmax / rho[i]));
    local[1] = fmax(local[1], xmax);
  }
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  // (tolerance 0 asks for every step to use all its iterations: no floor then)
  const double floor = (tolerance > 0.0) ? 0.5 * DBL_EPSILON * all[0] : 0.0;
  tol_step = fmax(tolerance, floor);
  if (floor > tolerance && !warned_roundoff && comm->me == 0)
    error->warning(FLERR,
                   "Fix sissm: at step {} round-off in the atom coordinates (up to {:.3g} from "
                   "the origin) limits the convergence measure to about {:.3g}, above the "
                   "tolerance {:.3g}: steps that reach it count as converged (a body nearer the "
                   "origin, or a smaller time step, allows a tighter tolerance; reported once "
                   "per run)",
                   update->ntimestep, all[1], floor, tolerance);
  if (floor > tolerance) warned_roundoff = 1;
  return tol_step;
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
  scheme->begin(rows_, arrays);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) fext[i][0] = fext[i][1] = fext[i][2] = 0.0;

  evaluations_ = 0;
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
    result = PeriSISSM::solve_newton_krylov(*this, *precond, maxiter, work);
  } else {
    PeriSISSM::SweepMemory memory_rows;
    memory_rows.rprev = rprev;
    memory_rows.dprev = dprev;
    result = PeriSISSM::solve_jacobi(*this, maxiter, memory_rows);
  }
  // (tolerance 0: every step runs to the limit by request, which says nothing of the
  // preconditioner)
  if (solver == KRYLOV)
    precond->finished(result.newton, result.krylov, result.converged() || tolerance == 0.0);
  last_newton += result.newton;
  last_krylov += result.krylov;
  if (!forces->group_coupled(groupbit)) {
    const PeriSISSM::MomentumBalance balance{h, scheme->force_factor(),
                                             scheme->name() == "euler"};
    PeriSISSM::balance_momentum(rows_, *this, balance, x, yn, yhat, flag ? nullptr : fext,
                                moment);
  }
  // the last move (the final correction, the momentum balance) is limited like the others
  if (!limiters.empty()) {
    comm->forward_comm();
    limit_path(true);
  }
  scheme->finish(rows_, arrays);
  if (move_others) place_others(t_end);
  return result;
}

/* ----------------------------------------------------------------------
   unconverged cutback: the step is redone from y^n, v^n (kept in xstart, vstart) as 2, 4, ...
   2^max_cutback equal sub-steps until every sub-step converges. Atoms outside the group (held,
   or moved by fix move or another integrator, already at t^{n+1}) sit at x^{n+1} - (1 - t) h v
   at the end t (a fraction of the step) of each sub-step, and at x^{n+1} afterwards; the other
   fixes' forces are those of t^{n+1} throughout. Returns true when a level converged (its
   sub-step count in substeps); false leaves the last level's unconverged result.
------------------------------------------------------------------------- */

bool FixSissm::cut_back(int &substeps, PeriSISSM::SolveResult &result, int &evaluations,
                        double **flag)
{
  bool done = false;
  for (int level = 1; level <= max_cutback && !done; level++) {
    const int n = 1 << level;
    restore_start();
    done = true;
    for (int s = 0; s < n; s++) {
      result = solve_step(dtv / n, (double) (s + 1) / n, flag);
      evaluations += evaluations_;
      if (!result.converged()) {
        done = false;
        break;
      }
    }
    substeps = n;
  }
  place_others(1.0);
  scheme->set_step(dtv);
  return done;
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
  const int lagged = external_mode == EXT_LAGGED, mixed = external_mode == EXT_MIXED;
  rows_.n = nlocal;
  rows_.mask = mask;
  rows_.bit = groupbit;
  rows_.volume = atom->vfrac;
  rows_.density = atom->rmass;
  // the particle sizes of the convergence measure, once per step rather than per iteration
  for (int i = 0; i < nlocal; i++) psize[i] = cbrt(atom->vfrac[i]);
  rows_.size = psize;

  // lagged: fint of ghosts belongs to their owners (short-range contact with newton on)
  if ((lagged || mixed) && force->newton_pair) comm->reverse_comm(this);
  if (mixed) lagged_external_force();
  if (lagged)
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < 3; k++)
        flagged[i][k] = (mask[i] & groupbit) ? f[i][k] - fint[i][k] : 0.0;
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

  PeriSISSM::SolveResult result;
  int evaluations = 0, substeps = 1;
  last_newton = last_krylov = 0;
  // tolerance 0 asks for every step to use all its iterations: such a step is neither redone
  // nor refused
  const bool fixed_count = tolerance == 0.0;
  {
    ImplicitStep step(forces, groupbit);
    // precond amg: the preconditioner that converged the last step goes first
    precond = (amg_precond && !block_first) ? amg_precond.get() : block_precond.get();
    result = solve_step(dtv, 1.0, lagged ? flagged : nullptr);
    evaluations = evaluations_;
    if (!result.converged() && !fixed_count && precond->refresh()) {
      // the preconditioner was built in an earlier step: once more with one built now
      restore_start();
      result = solve_step(dtv, 1.0, lagged ? flagged : nullptr);
      evaluations += evaluations_;
    }
    if (!result.converged() && amg_precond && !fixed_count) {
      // a step that one preconditioner could not converge is redone with the other (measured:
      // a free, rotating soft block at 100x the explicit limit, where the AMG-preconditioned
      // Newton steps diverge after some steps and the blocks converge)
      restore_start();
      precond = (precond == block_precond.get()) ? amg_precond.get() : block_precond.get();
      result = solve_step(dtv, 1.0, lagged ? flagged : nullptr);
      evaluations += evaluations_;
      if (result.converged()) block_first = precond == block_precond.get();
      fallback_run++;
      if (!warned_fallback && comm->me == 0)
        error->warning(FLERR,
                       "Fix sissm {}: step {} did not converge with precond {}; redone with "
                       "the {} preconditioner ({}; the one that converged goes first from now "
                       "on; counted in f_{}[9]; reported once per run)",
                       id, update->ntimestep, precond == block_precond.get() ? "amg" : "block",
                       precond == block_precond.get() ? "block" : "amg",
                       result.converged() ? "converged" : "not converged either", id);
      warned_fallback = 1;
    }
    if (!result.converged() && unconverged == UNCONVERGED_CUTBACK && !fixed_count) {
      if (cut_back(substeps, result, evaluations, lagged ? flagged : nullptr)) {
        cutback_run++;
        if (comm->me == 0)
          utils::logmesg(lmp,
                         "Fix sissm {}: step {} did not converge in {} iterations; redone as {} "
                         "sub-steps of {:.6g} (counted in f_{}[6])\n",
                         id, update->ntimestep, maxiter, substeps, dtv / substeps, id);
      } else {
        error->all(FLERR,
                   "Fix sissm {}: step {} did not converge in {} iterations per step, not even "
                   "as {} sub-steps of {:.6g} (convergence measure {:.3g} > tolerance {:.3g}): "
                   "raise iterations, lower the time step, or accept unconverged steps with "
                   "'unconverged warn'",
                   id, update->ntimestep, maxiter, substeps, dtv / substeps, result.measure,
                   result.tolerance);
      }
    }
  }
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

  last_iterations = evaluations;
  last_measure = measure;
  last_substeps = substeps;
  nsteps_run++;
  iterations_run += evaluations;
  if (measure > tol_step) {
    unconverged_run++;
    if (unconverged == UNCONVERGED_ERROR && !fixed_count)
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

/* ----------------------------------------------------------------------
   external mixed, at the start of a step (positions y^n, velocities v^n): the force of the
   lagged fixes is what the evaluation that ended the previous step added beyond the pair
   force (f - fint, at y^n and v^n) minus what the re-evaluated fixes give at y^n and v^n
   (all of them add forces independent of the force so far, choose_external())
------------------------------------------------------------------------- */

void FixSissm::lagged_external_force()
{
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) flagged[i][k] = (mask[i] & groupbit) ? f[i][k] - fint[i][k] : 0.0;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  for (Fix *fix : implicit_fixes) fix->post_force(0);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit)
      for (int k = 0; k < 3; k++) flagged[i][k] -= f[i][k];
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
  if (external_mode == EXT_LAGGED || external_mode == EXT_MIXED) arrays += 2 * 3;  // fint, flagged
  if (xstart) arrays += 2 * 3 + (hstart ? ncols : 0);                             // cut back
  arrays += ncols + (vn ? 2 * 3 : 0);    // the scheme's history, v^n and f at y^n
  if (gnode) arrays += 1;
  if (relax) arrays += 6;
  if (solver == KRYLOV) arrays += 7 * 3 + 1;
  return (double) arrays * nmax * sizeof(double);
}
