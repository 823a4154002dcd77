/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm (math.md section 3). Per step, with h the time step, for the atoms of the group,
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
   fix move or other integrators already sit at t^{n+1}.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "fix_nosb_family.h"
#include "pair_peri_nosb.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

// Solve the symmetric positive definite 3x3 system D d = r, D given as xx yy zz xy xz yz.
void solve_spd3(const double D[6], const double r[3], double d[3])
{
  const double a = D[0], b = D[1], c = D[2], xy = D[3], xz = D[4], yz = D[5];
  const double c00 = b * c - yz * yz, c01 = xz * yz - xy * c, c02 = xy * yz - xz * b;
  const double c11 = a * c - xz * xz, c12 = xy * xz - a * yz, c22 = a * b - xy * xy;
  const double inv = 1.0 / (a * c00 + xy * c01 + xz * c02);
  d[0] = inv * (c00 * r[0] + c01 * r[1] + c02 * r[2]);
  d[1] = inv * (c01 * r[0] + c11 * r[1] + c12 * r[2]);
  d[2] = inv * (c02 * r[0] + c12 * r[1] + c22 * r[2]);
}

// Solve the general 3x3 system M x = r (M row-major) by cofactors; false (x untouched) when
// |det M| <= tiny.
bool solve3(const double M[9], const double r[3], double tiny, double x[3])
{
  const double c00 = M[4] * M[8] - M[5] * M[7], c01 = M[5] * M[6] - M[3] * M[8],
               c02 = M[3] * M[7] - M[4] * M[6];
  const double det = M[0] * c00 + M[1] * c01 + M[2] * c02;
  if (!(std::fabs(det) > tiny)) return false;
  const double c10 = M[2] * M[7] - M[1] * M[8], c11 = M[0] * M[8] - M[2] * M[6],
               c12 = M[1] * M[6] - M[0] * M[7];
  const double c20 = M[1] * M[5] - M[2] * M[4], c21 = M[2] * M[3] - M[0] * M[5],
               c22 = M[0] * M[4] - M[1] * M[3];
  x[0] = (c00 * r[0] + c10 * r[1] + c20 * r[2]) / det;
  x[1] = (c01 * r[0] + c11 * r[1] + c21 * r[2]) / det;
  x[2] = (c02 * r[0] + c12 * r[1] + c22 * r[2]) / det;
  return true;
}

// Per-atom columns of the momentum balance (balance_momentum): 12 terms of a sum, then the
// atom's position relative to the centre of mass as the rotation proceeds.
constexpr int NMOMENT = 15;

// The pair flags of an implicit step, reset however the step ends (also when an error is
// thrown inside it and the caller of LAMMPS carries on).
class ImplicitStepFlags {
 public:
  explicit ImplicitStepFlags(PairPeriNosb *pair, int groupbit) : pair_(pair)
  {
    pair_->external_breaking = 1;
    pair_->contact_groupbit = groupbit;
    pair_->contact_crossings = 0;
  }
  ~ImplicitStepFlags()
  {
    pair_->external_breaking = 0;
    pair_->stiffness_flag = 0;
    pair_->contact_groupbit = 0;
  }
  ImplicitStepFlags(const ImplicitStepFlags &) = delete;
  ImplicitStepFlags &operator=(const ImplicitStepFlags &) = delete;

 private:
  PairPeriNosb *pair_;
};

}    // namespace

/* ---------------------------------------------------------------------- */

FixSissm::FixSissm(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair(nullptr), solver(KRYLOV), maxiter(100), tolerance(1.0e-6),
    relax(0), implicit_external(1), external_mode(EXT_NONE), dtv(0.0), tol_step(1.0e-6),
    last_iterations(0), last_measure(0.0), nsteps_run(0), iterations_run(0), unconverged_run(0),
    warned(0), warned_roundoff(0), nmax(0), evaluations(0), contact_incomplete(0), fint(nullptr),
    fext(nullptr), flagged(nullptr),
    yn(nullptr), yhat(nullptr), res(nullptr), block(nullptr), rprev(nullptr), dprev(nullptr),
    xbase(nullptr), rbase(nullptr), jbase(nullptr), cres(nullptr), zdir(nullptr), pdir(nullptr),
    sdir(nullptr), term(nullptr), moment(nullptr)
{
  time_integrate = 1;
  force_reneighbor = 1;    // after steps that moved atoms far (short-range contact)
  next_reneighbor = -1;
  vector_flag = 1;
  size_vector = 4;
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
    } else {
      error->all(FLERR,
                 "Illegal fix sissm command: unknown keyword '{}' (allowed: iterations, "
                 "tolerance, solver, relax, external)",
                 arg[iarg]);
    }
  }
  if (relax && solver != JACOBI)
    error->all(FLERR, "Illegal fix sissm command: relax yes requires solver jacobi");
}

/* ---------------------------------------------------------------------- */

FixSissm::~FixSissm()
{
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
  pair = dynamic_cast<PairPeriNosb *>(force->pair_match("peri/nosb", 1));
  if (!pair)
    error->all(FLERR, "Fix sissm requires pair_style peri/nosb (found {})",
               force->pair_style ? force->pair_style : "no pair style");
  if (!atom->rmass_flag || !atom->vfrac_flag)
    error->all(FLERR, "Fix sissm requires atom_style peri (per-atom density and volume)");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix sissm does not support run_style respa");
  dtv = update->dt;
  comm_reverse = 3;
  choose_external();
  pair->track_contact_motion(1);
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
      "spring",     "spring/self",  "drag",        "efield"};
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
  for (double ***a : {&fint, &fext, &flagged, &yn, &yhat, &res, &block, &rprev, &dprev, &xbase,
                      &rbase, &jbase, &cres, &zdir, &pdir, &sdir, &moment})
    memory->destroy(*a);
  memory->destroy(term);
}

void FixSissm::grow()
{
  if (atom->nmax <= nmax) return;
  destroy_arrays();
  nmax = atom->nmax;
  memory->create(block, nmax, 6, "sissm:block");
  memory->create(yn, nmax, 3, "sissm:yn");
  memory->create(yhat, nmax, 3, "sissm:yhat");
  memory->create(res, nmax, 3, "sissm:res");
  memory->create(fext, nmax, 3, "sissm:fext");
  memory->create(moment, nmax, NMOMENT, "sissm:moment");
  if (external_mode == EXT_LAGGED || external_mode == EXT_MIXED)
    memory->create(fint, nmax, 3, "sissm:fint");
  if (external_mode == EXT_MIXED) memory->create(flagged, nmax, 3, "sissm:flagged");
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
  nsteps_run = iterations_run = unconverged_run = 0;
  warned = warned_roundoff = 0;
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
   one force evaluation at the current positions: ghost positions, the peri/nosb force density
   (without energy/virial; H for the blocks only when asked), ghost forces folded back, with
   external implicit the post_force of the other fixes (with v = (y - y^n)/h, so velocity
   dependent forces such as fix viscous are implicit too), then the backward-Euler residual
   r_i = rho_i (yhat_i - y_i) + h^2 f_i of the owned atoms of the group into res.
   Its convergence measure is scaled_max(res, 1) = max_i |r_i| / (rho_i V_i^(1/3)): the
   residual as a length relative to the particle size. Near a stable state the Jacobian
   rho I + h^2 K is at least rho, so |r|/rho bounds the distance to the solution; the size of
   a correction does not
------------------------------------------------------------------------- */

void FixSissm::evaluate(int blocks)
{
  evaluations++;
  comm->forward_comm();
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double *rho = atom->rmass;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double h2 = dtv * dtv;

  contact_incomplete = pair->contact_follow_motion() < 0;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  pair->stiffness_flag = blocks;
  pair->compute(0, 0);
  if (force->newton_pair) comm->reverse_comm();
  if (external_mode == EXT_IMPLICIT || external_mode == EXT_MIXED) {
    // the other fixes' force at this iterate, kept in fext (f after minus f before)
    const double hinv = 1.0 / dtv;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) {
          v[i][k] = (x[i][k] - yn[i][k]) * hinv;
          fext[i][k] = f[i][k];
        }
    for (Fix *fix : implicit_fixes) fix->post_force(0);
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) {
          if (external_mode == EXT_MIXED) f[i][k] += flagged[i][k];
          fext[i][k] = f[i][k] - fext[i][k];
        }
  }
  if (blocks) pair->implicit_blocks(block);

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) {
      res[i][k] = rho[i] * (yhat[i][k] - x[i][k]) + h2 * f[i][k];
      r2 += res[i][k] * res[i][k];
    }
    if (!std::isfinite(r2))
      error->one(FLERR, "Fix sissm: non-finite position or force of atom {} at step {}",
                 atom->tag[i], update->ntimestep);
  }
}

/* ----------------------------------------------------------------------
   D_i = rho_i I + h^2 block_i of owned atom i (xx yy zz xy xz yz)
------------------------------------------------------------------------- */

void FixSissm::particle_block(int i, double D[6]) const
{
  const double rho = atom->rmass[i], h2 = dtv * dtv;
  const double *a = block[i];
  for (int k = 0; k < 6; k++) D[k] = (k < 3 ? rho : 0.0) + h2 * a[k];
}

/* ----------------------------------------------------------------------
   z_i = D_i^-1 r_i for the owned atoms of the group (the SISSM correction of r)
------------------------------------------------------------------------- */

void FixSissm::precondition(double **r, double **z)
{
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double D[6];
    particle_block(i, D);
    solve_spd3(D, r[i], z[i]);
  }
}

/* ----------------------------------------------------------------------
   sum_i V_i a_i . b_i over the group (all ranks): the inner product in which the Jacobian
   V J = rho V I + h^2 d2E/dy2 of the residual is symmetric
------------------------------------------------------------------------- */

double FixSissm::dot(double **a, double **b)
{
  double *vfrac = atom->vfrac;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    term[i] = (mask[i] & groupbit)
        ? vfrac[i] * (a[i][0] * b[i][0] + a[i][1] * b[i][1] + a[i][2] * b[i][2])
        : 0.0;
  return reproducible_sum(term, nlocal);
}

/* ----------------------------------------------------------------------
   sum of t[0..n-1] (n = nlocal) over all ranks, independent of the order of the terms and of
   how they are spread over the ranks. With T the largest |term| and N = natoms, every term
   is rounded to an integer multiple of 2^-q, 2^q T N < 2^61, and the integers are summed
   exactly: the error is below N 2^-q / 2, i.e. N 2^-60 (1e-12 for a million atoms) relative
   to N T. Ordinary floating-point sums differ in their last bits between rank counts; the
   Krylov coefficients come from these sums, the iteration count from the coefficients, and
   1 and 2 ranks would end the solve at different iterates within the tolerance
------------------------------------------------------------------------- */

double FixSissm::reproducible_sum(const double *t, int n)
{
  double sum;
  reproducible_sums(t, n, 1, 1, &sum);
  return sum;
}

/* ----------------------------------------------------------------------
   the same for ncol columns at once: column k of row i is t[i * stride + k] (two global
   reductions of ncol values, whatever ncol)
------------------------------------------------------------------------- */

void FixSissm::reproducible_sums(const double *t, int n, int stride, int ncol, double *out)
{
  std::vector<double> local(ncol, 0.0), big(ncol);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < ncol; k++) local[k] = fmax(local[k], fabs(t[i * stride + k]));
  MPI_Allreduce(local.data(), big.data(), ncol, MPI_DOUBLE, MPI_MAX, world);
  int ecount;
  frexp((double) atom->natoms, &ecount);    // natoms < 2^ecount
  std::vector<int> q(ncol, 0);
  for (int k = 0; k < ncol; k++) {
    if (!(big[k] > 0.0)) continue;
    int ebig;
    frexp(big[k], &ebig);    // big < 2^ebig
    q[k] = 61 - ebig - ecount;
  }
  std::vector<long long> sum_local(ncol, 0), sum(ncol);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < ncol; k++)
      if (big[k] > 0.0) sum_local[k] += llrint(ldexp(t[i * stride + k], q[k]));
  MPI_Allreduce(sum_local.data(), sum.data(), ncol, MPI_LONG_LONG, MPI_SUM, world);
  for (int k = 0; k < ncol; k++) out[k] = (big[k] > 0.0) ? ldexp((double) sum[k], -q[k]) : 0.0;
}

/* ----------------------------------------------------------------------
   max_i |a_i| / V_i^(1/3) over the group (all ranks), times 1/rho_i when a is a residual
------------------------------------------------------------------------- */

double FixSissm::scaled_max(double **a, int per_density)
{
  double *rho = atom->rmass;
  double *vfrac = atom->vfrac;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  double local = 0.0, all = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double size = per_density ? rho[i] * cbrt(vfrac[i]) : cbrt(vfrac[i]);
    const double m = sqrt(a[i][0] * a[i][0] + a[i][1] * a[i][1] + a[i][2] * a[i][2]) / size;
    if (m > local) local = m;
  }
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return all;
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
   one SISSM sweep from the last evaluation (res, block): y_i += alpha_i D_i^-1 r_i.
   relax yes (after the first sweep of a step): secant estimate of the particle's stiffness
   along its last move Delta = dprev: the residual changed by -(stiffness) Delta; when the
   true response is stiffer than the block D assumed (Delta.D.Delta), the step is scaled back
   by their ratio
------------------------------------------------------------------------- */

void FixSissm::sweep(int first)
{
  double **x = atom->x;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *r = res[i];
    double D[6];
    particle_block(i, D);
    double d[3];
    solve_spd3(D, r, d);

    double alpha = 1.0;
    if (relax && !first) {
      const double *dp = dprev[i], *rp = rprev[i];
      const double dd = dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2];
      if (dd > 0.0) {
        const double dDd = D[0] * dp[0] * dp[0] + D[1] * dp[1] * dp[1] + D[2] * dp[2] * dp[2] +
            2.0 * (D[3] * dp[0] * dp[1] + D[4] * dp[0] * dp[2] + D[5] * dp[1] * dp[2]);
        const double dr = -((r[0] - rp[0]) * dp[0] + (r[1] - rp[1]) * dp[1] +
                             (r[2] - rp[2]) * dp[2]);
        if (dr > dDd) alpha = dDd / dr;
      }
    }
    for (int k = 0; k < 3; k++) {
      d[k] *= alpha;
      x[i][k] += d[k];
      if (relax) {
        rprev[i][k] = r[k];
        dprev[i][k] = d[k];
      }
    }
  }
  check_finite();
}

/* ----------------------------------------------------------------------
   solver jacobi: up to maxiter sweeps; each evaluates the residual of the iterate it starts
   from, and the sweep whose starting residual meets the tolerance is the last one
------------------------------------------------------------------------- */

double FixSissm::solve_jacobi()
{
  double measure = 0.0;
  for (int k = 0; k < maxiter; k++) {
    evaluate(1);
    measure = scaled_max(res, 1);
    if (k == 0) attainable_tolerance();
    sweep(k == 0);
    if (measure <= tol_step && !contact_incomplete) break;
  }
  return measure;
}

/* ----------------------------------------------------------------------
   solver krylov: inexact Newton on r(y) = 0 with J = -dr/dy = rho I + h^2 K (symmetric in
   the V-weighted inner product). Each Newton step solves J s = r(y_base) by conjugate
   gradients preconditioned with the SISSM blocks D (the first CG direction is the SISSM
   correction D^-1 r), with J p = (r(y_base) - r(y_base + e p)) / e, e = 1e-7 / max|p_i|/l_i:
   one force evaluation per CG iteration. CG stops when its residual estimate meets
   max(tolerance/4, eta * measure) (eta: Eisenstat-Walker), at non-positive curvature (then
   the SISSM correction is used if CG has no step yet) or at the evaluation budget.
   Safeguard: a Newton step that increases phi = sum_i V_i |r_i|^2 / rho_i is halved (at most
   4 times). Budget (maxiter evaluations, never more): CG keeps one evaluation to check its
   Newton iterate; when that check finds it worse than its base and no budget is left, the
   step ends at the base plus its SISSM correction D^-1 r; when the budget ends at an accepted
   evaluation, one SISSM sweep uses it, so krylov with iterations 1 equals jacobi with
   iterations 1. The evaluation that meets the tolerance also gives its SISSM correction.
------------------------------------------------------------------------- */

double FixSissm::solve_krylov()
{
  double **x = atom->x;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  double measure = 0.0, measure_prev = 0.0, phi_base = 0.0, eta = 1.0e-2;
  int have_base = 0, halvings = 0;

  auto axpy_positions = [&](double **base, double c, double **dir) {
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) x[i][k] = base[i][k] + c * dir[i][k];
  };

  while (true) {
    evaluate(1);
    measure = scaled_max(res, 1);
    if (evaluations == 1) attainable_tolerance();
    if (measure <= tol_step && !contact_incomplete) {
      // as jacobi does: the evaluation that meets the tolerance still gives its SISSM
      // correction (free, and at small steps, where the start y^n + h v^n may already meet a
      // loose tolerance, it is what moves the body by h^2 f / rho)
      sweep(1);
      break;
    }
    const double phi = merit();
    const int worse = have_base && phi > phi_base;
    if (worse && halvings < 4 && evaluations < maxiter) {
      halvings++;
      axpy_positions(xbase, ldexp(1.0, -halvings), sdir);
      continue;
    }
    if (worse && evaluations >= maxiter) {
      // the budget ends on a Newton iterate worse than its base: take the SISSM correction
      // of the base instead (the plain sweep, robust where a truncated Newton step is not)
      axpy_positions(xbase, 1.0, jbase);
      check_finite();
      measure = measure_prev;
      break;
    }
    if (evaluations >= maxiter - 1) {
      // no budget left for a CG product and the check of its Newton iterate
      sweep(1);
      break;
    }

    // accept the iterate as the base of a Newton step
    if (have_base && measure_prev > 0.0)
      eta = fmin(0.1, fmax(1.0e-4, 0.9 * (measure / measure_prev) * (measure / measure_prev)));
    measure_prev = measure;
    halvings = 0;
    have_base = 1;
    phi_base = phi;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) {
          xbase[i][k] = x[i][k];
          rbase[i][k] = cres[i][k] = res[i][k];
          sdir[i][k] = 0.0;
        }
    precondition(cres, zdir);
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) pdir[i][k] = jbase[i][k] = zdir[i][k];
    double rz = dot(cres, zdir);
    const double target = fmax(0.25 * tol_step, eta * measure);
    int cg = 0;

    while (evaluations < maxiter - 1 && rz > 0.0) {
      const double e = 1.0e-7 / scaled_max(pdir, 0);
      axpy_positions(xbase, e, pdir);
      evaluate(0);
      // res <- J p
      for (int i = 0; i < nlocal; i++)
        if (mask[i] & groupbit)
          for (int k = 0; k < 3; k++) res[i][k] = (rbase[i][k] - res[i][k]) / e;
      const double pjp = dot(pdir, res);
      if (!(pjp > 0.0)) {
        if (cg == 0)
          for (int i = 0; i < nlocal; i++)
            if (mask[i] & groupbit)
              for (int k = 0; k < 3; k++) sdir[i][k] = zdir[i][k];
        break;
      }
      const double alpha = rz / pjp;
      for (int i = 0; i < nlocal; i++)
        if (mask[i] & groupbit)
          for (int k = 0; k < 3; k++) {
            sdir[i][k] += alpha * pdir[i][k];
            cres[i][k] -= alpha * res[i][k];
          }
      cg++;
      if (scaled_max(cres, 1) <= target) break;
      precondition(cres, zdir);
      const double rz_new = dot(cres, zdir);
      const double beta = rz_new / rz;
      rz = rz_new;
      for (int i = 0; i < nlocal; i++)
        if (mask[i] & groupbit)
          for (int k = 0; k < 3; k++) pdir[i][k] = zdir[i][k] + beta * pdir[i][k];
    }
    axpy_positions(xbase, 1.0, sdir);
    check_finite();
  }
  return measure;
}

/* ----------------------------------------------------------------------
   the tolerance this step can meet. Positions are absolute coordinates: an atom at |x| from
   the origin is known to eps |x| (eps the machine epsilon), and so are its bond vectors, so
   the force density of particle i is known to about |block_i| eps |x|, and the convergence
   measure to
     floor_i = eps (|x_i| / l_i) (1 + h^2 |block_i| / rho_i)      (l_i = V_i^(1/3)),
   |x| the largest coordinate, |block| the largest diagonal entry of the SISSM block (the row
   sum of the bond stiffnesses). Measured on a 4x3x3 block at 20 and 100 x the explicit limit
   (neo-Hookean, random velocities), at the origin and moved 4e4 particle sizes away, the
   measure stalls at 0.2 to 0.4 x this estimate (1e-12 at the origin, 2e-8 far away, at
   20 x). A step whose measure is below the larger of the tolerance and half the largest
   estimate counts as converged; the first time in a run that this exceeds the tolerance, a
   warning says so.
   One global max, at the first evaluation of a step.
------------------------------------------------------------------------- */

void FixSissm::attainable_tolerance()
{
  double **x = atom->x;
  double *rho = atom->rmass;
  double *vfrac = atom->vfrac;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double h2 = dtv * dtv;
  double local[2] = {0.0, 0.0}, all[2];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double xmax = fmax(fabs(x[i][0]), fmax(fabs(x[i][1]), fabs(x[i][2])));
    const double bmax = fmax(block[i][0], fmax(block[i][1], block[i][2]));
    local[0] = fmax(local[0], xmax / cbrt(vfrac[i]) * (1.0 + h2 * bmax / rho[i]));
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
}

/* ----------------------------------------------------------------------
   merit of the last evaluation: sum_i V_i |r_i|^2 / rho_i (all ranks)
------------------------------------------------------------------------- */

double FixSissm::merit()
{
  double *rho = atom->rmass;
  double *vfrac = atom->vfrac;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    term[i] = (mask[i] & groupbit) ? vfrac[i] / rho[i] *
            (res[i][0] * res[i][0] + res[i][1] * res[i][1] + res[i][2] * res[i][2])
                                   : 0.0;
  return reproducible_sum(term, nlocal);
}

/* ---------------------------------------------------------------------- */

void FixSissm::post_integrate()
{
  grow();
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double *rho = atom->rmass;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double h = dtv, h2 = dtv * dtv;
  const int lagged = external_mode == EXT_LAGGED, mixed = external_mode == EXT_MIXED;

  // lagged: fint of ghosts belongs to their owners (short-range contact with newton on)
  if ((lagged || mixed) && force->newton_pair) comm->reverse_comm(this);
  if (mixed) lagged_external_force();

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int k = 0; k < 3; k++) {
      yn[i][k] = x[i][k];
      yhat[i][k] = x[i][k] + h * v[i][k];
      if (lagged) yhat[i][k] += h2 * (f[i][k] - fint[i][k]) / rho[i];
      fext[i][k] = 0.0;
      x[i][k] += h * v[i][k];
    }
  }

  evaluations = 0;
  double measure;
  int free_group;
  {
    ImplicitStepFlags flags(pair, groupbit);
    measure = (solver == KRYLOV) ? solve_krylov() : solve_jacobi();
    free_group = group_is_free();
  }
  if (free_group) balance_momentum();

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) v[i][d] = (x[i][d] - yn[i][d]) / h;
  }

  // the blow-up guard of pair peri/nosb, now that the atoms are at y^{n+1} (before LAMMPS
  // decides on a neighbor list build): a diverged step ends in an error, not in LAMMPS's
  // neighbor binning
  pair->family->check_motion(measure <= tol_step ? 1 : 0);
  // short-range contact: a result beyond what the candidates could follow is refused, and
  // the next step starts from a fresh neighbor list if this one moved atoms far
  // (PairPeriNosb::contact_follow_motion())
  const std::string cause = (measure > tol_step)
      ? fmt::format("this step stopped at the iteration limit with convergence measure {:.3g} "
                    "above the tolerance {:.3g}, so the motion may be an artefact of the "
                    "unconverged solve",
                    measure, tol_step)
      : "";
  if (pair->contact_end_of_step(cause)) next_reneighbor = update->ntimestep;

  const int k = evaluations;
  last_iterations = k;
  last_measure = measure;
  nsteps_run++;
  iterations_run += k;
  if (measure > tol_step) {
    unconverged_run++;
    if (!warned && comm->me == 0)
      error->warning(FLERR,
                     "Fix sissm: step {} stopped at {} iterations with convergence measure {:.3g} "
                     "> tolerance {:.3g} (counted in f_{}[4]; reported once per run)",
                     update->ntimestep, k, measure, tolerance, id);
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

/* ----------------------------------------------------------------------
   a free group: no unbroken bond joins an atom of the group with one outside it, and no
   short-range contact of peri/nosb acted between them in the evaluations of this step.
   Then the pair forces on the group sum to zero and have no net torque at any positions
   (they derive from a translation and rotation invariant energy)
------------------------------------------------------------------------- */

bool FixSissm::group_is_free()
{
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const FixNosbFamily *family = pair->family;
  int coupled = pair->contact_crossings > 0;
  for (int i = 0; i < nlocal && !coupled; i++) {
    if (!(mask[i] & groupbit)) continue;
    const int *jl = family->jlocal[i];
    for (int b = 0; b < family->npartner[i]; b++)
      if (jl[b] >= 0 && !(mask[jl[b]] & groupbit)) {
        coupled = 1;
        break;
      }
  }
  int any;
  MPI_Allreduce(&coupled, &any, 1, MPI_INT, MPI_MAX, world);
  return !any;
}

/* ----------------------------------------------------------------------
   momentum balance of a free group, for every step, converged or not:
     P^{n+1} = P^n + h F,        F = sum_i V_i fext_i,
     L^{n+1} = L^n + h T,        T = sum_i V_i r_i x fext_i,
   P = sum_i m_i v_i, L = sum_i m_i q_i x v_i the angular momentum about the centre of mass
   (q_i = y_i - c), m_i = rho_i V_i, fext the other fixes' force density of the last evaluation
   and r_i = y_i^{n+1} - c^{n+1} (under external lagged fext is zero here: it is in yhat, so
   that m (yhat - y^n) / h = m v^n + h V fext, and the lagged force and torque at y^n are in the
   targets). With v^{n+1} = (y^{n+1} - y^n)/h and sum_i m_i q_i^n = 0,
     sum_i m_i (y_i^{n+1} - y_i^n) = h P^{n+1},   L^{n+1} = (1/h) sum_i m_i q_i^n x r_i.
   The internal forces of a free group have zero sum and zero torque at any positions (their
   energy is invariant under translation and rotation), so a converged backward-Euler step
   keeps P exactly; a truncated solve does not, and a free body at rest would pick up a rigid
   velocity. Backward Euler itself changes L by h sum_i m_i v_i^{n+1} x v_i^n (it damps
   rotation). The correction moves the result rigidly: its centre by d (from the first
   balance, exactly), and the rest by a rotation R about the centre, r_i -> R r_i, found by
   Newton's method on G(R) = (1/h) sum m q^n x R r - h sum V (R r) x fext - L^n = 0 with
     dG = J dtheta,  J = (1/h) sum_i m_i ((q_i^n . r_i) I - r_i q_i^nT)
                          - h sum_i V_i (r_i fext_i^T - (r_i . fext_i) I)
   (rotation increments composed exactly, Rodrigues' formula): a rotation changes no bond
   length, so the deformation and its energy are untouched. A converged step needs a rotation
   of ~1e-4 rad or less, reached to round-off in two iterations; at most 8 are made. All
   terms are relative to the centres (coordinates far from the origin would cost digits), and
   the sums are order-independent, so every rank count corrects alike.
------------------------------------------------------------------------- */

void FixSissm::balance_momentum()
{
  double **x = atom->x;
  double *rho = atom->rmass;
  double *vfrac = atom->vfrac;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double h = dtv;
  const int lagged = external_mode == EXT_LAGGED;
  double *t = (nlocal > 0) ? moment[0] : nullptr;
  auto cross = [](const double *u, const double *v, double *w) {
    w[0] = u[1] * v[2] - u[2] * v[1];
    w[1] = u[2] * v[0] - u[0] * v[2];
    w[2] = u[0] * v[1] - u[1] * v[0];
  };

  // mass and centre of mass c^n of the step's start
  double s[NMOMENT];
  for (int i = 0; i < nlocal; i++) {
    double *row = moment[i];
    const double m = (mask[i] & groupbit) ? rho[i] * vfrac[i] : 0.0;
    row[0] = m;
    for (int k = 0; k < 3; k++) row[1 + k] = m * yn[i][k];
  }
  reproducible_sums(t, nlocal, NMOMENT, 4, s);
  const double mass = s[0];
  if (!(mass > 0.0)) return;
  const double cn[3] = {s[1] / mass, s[2] / mass, s[3] / mass};

  // the step's displacement of the centre, the targets h P^{n+1} - h^2 F and L^n, and F
  for (int i = 0; i < nlocal; i++) {
    double *row = moment[i];
    for (int k = 0; k < 12; k++) row[k] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    const double m = rho[i] * vfrac[i];
    double q[3], mv[3];
    for (int k = 0; k < 3; k++) {
      q[k] = yn[i][k] - cn[k];
      mv[k] = m * (yhat[i][k] - yn[i][k]) / h;    // m v^n (+ the lagged force, see above)
      row[k] = m * (x[i][k] - yn[i][k]);
      row[3 + k] = mv[k];
      row[6 + k] = lagged ? 0.0 : vfrac[i] * fext[i][k];
    }
    cross(q, mv, row + 9);
  }
  reproducible_sums(t, nlocal, NMOMENT, 12, s);
  double dcen[3], d[3], Ln[3];
  for (int k = 0; k < 3; k++) {
    dcen[k] = s[k] / mass;                                   // c - c^n
    d[k] = (h * (s[3 + k] + h * s[6 + k]) - s[k]) / mass;    // move of the centre
    Ln[k] = s[9 + k];
  }

  // rotation about the centre c = c^n + dcen: r_i = y_i - c, kept in the last three columns
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit)
      for (int k = 0; k < 3; k++)
        moment[i][12 + k] = (x[i][k] - yn[i][k]) - dcen[k] + (yn[i][k] - cn[k]);
  const double h2 = h * h;
  for (int iter = 0; iter < 8; iter++) {
    for (int i = 0; i < nlocal; i++) {
      double *row = moment[i];
      for (int k = 0; k < 12; k++) row[k] = 0.0;
      if (!(mask[i] & groupbit)) continue;
      const double m = rho[i] * vfrac[i];
      const double *r = row + 12;
      const double q[3] = {yn[i][0] - cn[0], yn[i][1] - cn[1], yn[i][2] - cn[2]};
      double fe[3] = {0.0, 0.0, 0.0};
      if (!lagged)
        for (int k = 0; k < 3; k++) fe[k] = vfrac[i] * fext[i][k];
      double w[3], u[3];
      cross(q, r, w);
      cross(r, fe, u);
      for (int k = 0; k < 3; k++) row[k] = m * w[k] / h - h * u[k];    // G + L^n
      const double qr = q[0] * r[0] + q[1] * r[1] + q[2] * r[2];
      const double rf = r[0] * fe[0] + r[1] * fe[1] + r[2] * fe[2];
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
          row[3 + 3 * a + c] = m / h * ((a == c ? qr : 0.0) - r[a] * q[c]) -
              h * (r[a] * fe[c] - (a == c ? rf : 0.0));
    }
    reproducible_sums(t, nlocal, NMOMENT, 12, s);
    const double G[3] = {Ln[0] - s[0], Ln[1] - s[1], Ln[2] - s[2]};    // -G
    // (a group on a line or at a point has no inertia about some axis: no rotation then)
    const double jtrace = fabs(s[3]) + fabs(s[7]) + fabs(s[11]);
    double dtheta[3];
    if (!solve3(s + 3, G, 1.0e-12 * jtrace * jtrace * jtrace, dtheta)) break;
    const double angle = sqrt(dtheta[0] * dtheta[0] + dtheta[1] * dtheta[1] +
                              dtheta[2] * dtheta[2]);
    if (!(angle > 0.0)) break;
    const double k[3] = {dtheta[0] / angle, dtheta[1] / angle, dtheta[2] / angle};
    const double cs = cos(angle), sn = sin(angle);
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      double *r = moment[i] + 12;
      double kr[3];
      cross(k, r, kr);
      const double kdr = k[0] * r[0] + k[1] * r[1] + k[2] * r[2];
      for (int c = 0; c < 3; c++) r[c] = r[c] * cs + kr[c] * sn + k[c] * kdr * (1.0 - cs);
    }
    if (angle < 1.0e-15) break;
  }

  // y <- c + d + R r, written as a displacement of y (no large coordinates subtracted)
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *r = moment[i] + 12;
    for (int k = 0; k < 3; k++) {
      const double r0 = (x[i][k] - yn[i][k]) - dcen[k] + (yn[i][k] - cn[k]);
      x[i][k] += d[k] + (r[k] - r0);
    }
  }
}

/* ---------------------------------------------------------------------- */

double FixSissm::compute_vector(int n)
{
  if (n == 0) return last_iterations;
  if (n == 1) return last_measure;
  if (n == 2) return nsteps_run ? (double) iterations_run / nsteps_run : 0.0;
  return (double) unconverged_run;
}

/* ---------------------------------------------------------------------- */

double FixSissm::memory_usage()
{
  int arrays = 3 * 3 + 6;    // yn, yhat, res, block
  if (!implicit_external) arrays += 3;
  if (relax) arrays += 6;
  if (solver == KRYLOV) arrays += 22;
  return (double) arrays * nmax * sizeof(double);
}
