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

#include <cmath>
#include <cstring>
#include <initializer_list>

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

}    // namespace


/* ---------------------------------------------------------------------- */

FixSissm::FixSissm(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair(nullptr), solver(KRYLOV), maxiter(100), tolerance(1.0e-6),
    relax(0), implicit_external(1), dtv(0.0), last_iterations(0), last_measure(0.0),
    nsteps_run(0), iterations_run(0), unconverged_run(0), warned(0), nmax(0), evaluations(0),
    fint(nullptr), yn(nullptr), yhat(nullptr), res(nullptr), block(nullptr), rprev(nullptr),
    dprev(nullptr), xbase(nullptr), rbase(nullptr), jbase(nullptr), cres(nullptr), zdir(nullptr),
    pdir(nullptr), sdir(nullptr), term(nullptr)
{
  time_integrate = 1;
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
  for (double ***a : {&fint, &yn, &yhat, &res, &block, &rprev, &dprev, &xbase, &rbase, &jbase,
                      &cres, &zdir, &pdir, &sdir})
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
  if (!implicit_external) memory->create(fint, nmax, 3, "sissm:fint");
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
  warned = 0;
}

/* ----------------------------------------------------------------------
   external lagged: pair peri/nosb has just computed its force density (and nothing else has
   been added yet, other pair-like contributions do not exist with atom_style peri): keep it,
   for owned and ghost atoms, so that fext = f - fint can be formed at the start of the next
   step
------------------------------------------------------------------------- */

void FixSissm::capture_internal_force()
{
  if (implicit_external) return;
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

  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  pair->stiffness_flag = blocks;
  pair->compute(0, 0);
  if (force->newton_pair) comm->reverse_comm();
  if (implicit_external && modify->n_post_force_any) {
    const double hinv = 1.0 / dtv;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        for (int k = 0; k < 3; k++) v[i][k] = (x[i][k] - yn[i][k]) * hinv;
    modify->post_force(0);
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
  double local = 0.0, big = 0.0;
  for (int i = 0; i < n; i++) local = fmax(local, fabs(t[i]));
  MPI_Allreduce(&local, &big, 1, MPI_DOUBLE, MPI_MAX, world);
  if (!(big > 0.0)) return 0.0;
  int ebig, ecount;
  frexp(big, &ebig);                        // big < 2^ebig
  frexp((double) atom->natoms, &ecount);    // natoms < 2^ecount
  const int q = 61 - ebig - ecount;
  long long sum_local = 0, sum = 0;
  for (int i = 0; i < n; i++) sum_local += llrint(ldexp(t[i], q));
  MPI_Allreduce(&sum_local, &sum, 1, MPI_LONG_LONG, MPI_SUM, world);
  return ldexp((double) sum, -q);
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
    sweep(k == 0);
    if (measure <= tolerance) break;
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
    if (measure <= tolerance) {
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
    const double target = fmax(0.25 * tolerance, eta * measure);
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

  // lagged: fint of ghosts belongs to their owners (short-range contact with newton on)
  if (!implicit_external && force->newton_pair) comm->reverse_comm(this);

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int k = 0; k < 3; k++) {
      yn[i][k] = x[i][k];
      yhat[i][k] = x[i][k] + h * v[i][k];
      if (!implicit_external) yhat[i][k] += h2 * (f[i][k] - fint[i][k]) / rho[i];
      x[i][k] += h * v[i][k];
    }
  }

  evaluations = 0;
  pair->external_breaking = 1;
  const double measure = (solver == KRYLOV) ? solve_krylov() : solve_jacobi();
  pair->external_breaking = 0;
  pair->stiffness_flag = 0;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) v[i][d] = (x[i][d] - yn[i][d]) / h;
  }

  // the blow-up guard of pair peri/nosb, now that the atoms are at y^{n+1} (before LAMMPS
  // decides on a neighbor list build): a diverged step ends in an error, not in LAMMPS's
  // neighbor binning
  pair->family->check_motion(measure <= tolerance ? 1 : 0);

  const int k = evaluations;
  last_iterations = k;
  last_measure = measure;
  nsteps_run++;
  iterations_run += k;
  if (measure > tolerance) {
    unconverged_run++;
    if (!warned && comm->me == 0)
      error->warning(FLERR,
                     "Fix sissm: step {} stopped at {} iterations with convergence measure {:.3g} "
                     "> tolerance {:.3g} (counted in f_{}[4]; reported once per run)",
                     update->ntimestep, k, measure, tolerance, id);
    warned = 1;
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
