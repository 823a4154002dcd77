/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm (math.md section 3). Per step, with h the time step, for the atoms of the group:
     predictor   yhat_i = y_i^n + h v_i^n + h^2 fext_i / rho_i
     iterate     r_i   = rho_i (yhat_i - y_i^k) + h^2 f_i(y^k)        (backward-Euler residual)
                 D_i   = rho_i I + h^2 sum_j omega_ij (H_i + H_j + (C_i + C_j)/2 I)
                 y_i^{k+1} = y_i^k + alpha_i D_i^-1 r_i
     start       y^0 = y^n + h v^n      (an equilibrium is a fixed point for any iteration count)
     end         v_i^{n+1} = (y_i^{n+1} - y_i^n) / h
   f is the exact peri/nosb force density, so a converged step is the backward-Euler step of
   the material fix nve integrates. fext (other fixes: gravity, addforce, indent, walls) is
   taken at y^n: the total force of the last evaluation minus the pair part captured in
   pre_reverse. The iteration runs in post_integrate, after every initial_integrate, so
   particles prescribed by fix move or other integrators already sit at t^{n+1}.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "pair_peri_nosb.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

#include <cmath>
#include <cstring>

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
    Fix(lmp, narg, arg), pair(nullptr), maxiter(20), tolerance(1.0e-6), relax(0), dtv(0.0),
    last_iterations(0), last_measure(0.0), nsteps_run(0), iterations_run(0), unconverged_run(0),
    warned(0), nmax(0), fint(nullptr), yn(nullptr), yhat(nullptr), rprev(nullptr), dprev(nullptr),
    block(nullptr)
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
    } else {
      error->all(FLERR,
                 "Illegal fix sissm command: unknown keyword '{}' (allowed: iterations, "
                 "tolerance, relax)",
                 arg[iarg]);
    }
  }
}

/* ---------------------------------------------------------------------- */

FixSissm::~FixSissm()
{
  memory->destroy(fint);
  memory->destroy(yn);
  memory->destroy(yhat);
  memory->destroy(rprev);
  memory->destroy(dprev);
  memory->destroy(block);
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

/* ---------------------------------------------------------------------- */

void FixSissm::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  memory->destroy(fint);
  memory->destroy(yn);
  memory->destroy(yhat);
  memory->destroy(rprev);
  memory->destroy(dprev);
  memory->destroy(block);
  memory->create(block, nmax, 6, "sissm:block");
  memory->create(fint, nmax, 3, "sissm:fint");
  memory->create(yn, nmax, 3, "sissm:yn");
  memory->create(yhat, nmax, 3, "sissm:yhat");
  memory->create(rprev, nmax, 3, "sissm:rprev");
  memory->create(dprev, nmax, 3, "sissm:dprev");
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
   pair peri/nosb has just computed its force density (and nothing else has been added yet,
   other pair-like contributions do not exist with atom_style peri): keep it, for owned and
   ghost atoms, so that fext = f - fint can be formed at the start of the next step
------------------------------------------------------------------------- */

void FixSissm::capture_internal_force()
{
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
   internal force density f(y) of the current positions into atom->f (owned atoms complete):
   ghost positions, one pair evaluation without energy/virial, ghost forces folded back
------------------------------------------------------------------------- */

void FixSissm::internal_force()
{
  comm->forward_comm();
  const int nall = atom->nlocal + atom->nghost;
  double **f = atom->f;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  pair->compute(0, 0);
  if (force->newton_pair) comm->reverse_comm();
  pair->implicit_blocks(block);
}

/* ----------------------------------------------------------------------
   one Jacobi sweep over the owned atoms of the group; returns the local convergence measure
   of the iterate the sweep started from, max_i |r_i| / (rho_i l_i) with l_i = V_i^(1/3):
   the backward-Euler residual as a length relative to the particle size. Near a stable state
   the Jacobian rho I + h^2 K is at least rho, so |r|/rho bounds the distance to the solution;
   the size of a correction does not (at large h, D_i >> rho_i and slow modes such as a rigid
   translation move by a tiny fraction of their error per sweep)
------------------------------------------------------------------------- */

double FixSissm::iterate(int first)
{
  internal_force();

  double **x = atom->x;
  double **f = atom->f;
  double *rho = atom->rmass;
  double *vfrac = atom->vfrac;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double h2 = dtv * dtv;
  double measure = 0.0;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double r[3] = {rho[i] * (yhat[i][0] - x[i][0]) + h2 * f[i][0],
                         rho[i] * (yhat[i][1] - x[i][1]) + h2 * f[i][1],
                         rho[i] * (yhat[i][2] - x[i][2]) + h2 * f[i][2]};
    const double res = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) / (rho[i] * cbrt(vfrac[i]));
    if (res > measure) measure = res;
    const double *a = block[i];
    const double D[6] = {rho[i] + h2 * a[0], rho[i] + h2 * a[1], rho[i] + h2 * a[2],
                         h2 * a[3],          h2 * a[4],          h2 * a[5]};
    double d[3];
    solve_spd3(D, r, d);

    double alpha = 1.0;
    if (relax && !first) {
      // secant estimate of the particle's stiffness along its last move Delta = dprev:
      // the residual changed by -(stiffness) Delta; when the true response is stiffer than
      // the block D assumed (Delta.D.Delta), the step is scaled back by their ratio
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
    if (!std::isfinite(x[i][0] + x[i][1] + x[i][2]) || !(res < HUGE_VAL))
      error->one(FLERR, "Fix sissm: non-finite position of atom {} at step {}", atom->tag[i],
                 update->ntimestep);
  }
  return measure;
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

  // fint of ghosts belongs to their owners (short-range contact with newton on)
  if (force->newton_pair) comm->reverse_comm(this);

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int k = 0; k < 3; k++) {
      const double fext = f[i][k] - fint[i][k];
      yn[i][k] = x[i][k];
      yhat[i][k] = x[i][k] + h * v[i][k] + h2 * fext / rho[i];
      x[i][k] += h * v[i][k];
    }
  }

  pair->external_breaking = 1;
  pair->stiffness_flag = 1;
  double measure = 0.0;
  int k = 0;
  while (k < maxiter) {
    const double local = iterate(k == 0);
    MPI_Allreduce(&local, &measure, 1, MPI_DOUBLE, MPI_MAX, world);
    k++;
    if (measure <= tolerance) break;
  }
  pair->external_breaking = 0;
  pair->stiffness_flag = 0;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) v[i][d] = (x[i][d] - yn[i][d]) / h;
  }

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
  return 21.0 * nmax * sizeof(double);
}
