/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/family, the stable time step estimate (peri/stable_step.h, over the families) and
   the blow-up guard.

   Blow-up guard (check_motion, every step after the integrators have moved the atoms and
   before LAMMPS decides on a neighbor list build): a non-finite position, velocity or force
   of an owned atom, an atom beyond one periodic image of the box (Domain::pbc shifts by one
   box length only), or atoms spread so far that LAMMPS's neighbor bins cannot index them
   (more than 2^30 bins; LAMMPS's own test of that multiplies the bin counts in 64-bit integers,
   which wrap around for a box that exploded within one step, and then writes outside its bin
   array: signal 11 in NBinStandard::bin_atoms) stop the run with an error that names the step,
   the worst atom (the same on any number of ranks) and the likely cause, judged from the time
   step against the estimate of stable_time_steps(). Cost: one pass over the owned atoms and
   one MPI_Allreduce of 8 doubles per step.
------------------------------------------------------------------------- */

#include "fix_nosb_family.h"

#include "peri/model.h"
#include "peri/stable_step.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   stable explicit time step of every owned atom (PeriSISSM::stable_time_step, peri/stable_step.h):
   current bonds (broken ones do not count), reference state, so it changes only when bonds
   break; a particle with no stiffness (all bonds broken) gets +infinity
------------------------------------------------------------------------- */

void FixNosbFamily::stable_time_steps(double *dt)
{
  const int nlocal = atom->nlocal;
  int *type = atom->type;
  double *rho = atom->rmass;
  if (atom->nmax > 0 && !sdiag) grow_arrays(atom->nmax);

  for (int i = 0; i < nlocal; i++) {
    double s = 0.0;
    if (built && kregular[i])
      s = PeriSISSM::stable_step_stiffness(model->material(type[i]), kinv[i],
                                           model->stabilization_modulus(type[i], kinv[i]),
                                           model->membrane(type[i]));
    sdiag[i] = s;
  }
  comm->forward_comm(this);

  for (int i = 0; i < nlocal; i++) {
    double d = 0.0;
    if (built) {
      // partners through the atom map (any image carries s_j), so that this also works
      // between runs, when jlocal may be stale
      for (int b = 0; b < npartner[i]; b++) {
        if (partner[i][b] == 0) continue;
        const int j = local_index(partner[i][b]);
        if (j < 0) continue;
        d += omega[i][b] * (sdiag[i] + sdiag[j]);
      }
    }
    dt[i] = PeriSISSM::stable_time_step(rho[i], d);
  }
}

/* ---------------------------------------------------------------------- */

double FixNosbFamily::min_stable_time_step()
{
  const int nlocal = atom->nlocal;
  std::vector<double> dt(nlocal);
  stable_time_steps(dt.data());
  double one = std::numeric_limits<double>::infinity(), all;
  for (int i = 0; i < nlocal; i++) one = std::min(one, dt[i]);
  MPI_Allreduce(&one, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  return all;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::post_integrate()
{
  if (!integrator_checks) check_motion();
}

/* ----------------------------------------------------------------------
   the blow-up guard (see the top of this file)
------------------------------------------------------------------------- */

void FixNosbFamily::check_motion(int converged)
{
  if (converged >= 0) integrator_checks = 1;

  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const double *lo = domain->boxlo;
  const double *hinv = domain->h_inv;
  const int *pbc = domain->periodicity;
  const int anypbc = pbc[0] || pbc[1] || pbc[2];

  // maxima over all ranks: -(smallest ID with a non-finite value), -(smallest ID beyond one
  // periodic image), -min and max of the finite positions

  constexpr double NONE = -DBL_MAX;
  double one[8] = {NONE, NONE, NONE, NONE, NONE, NONE, NONE, NONE}, all[8];
  for (int i = 0; i < nlocal; i++) {
    const double *xi = x[i];
    const double sum =
        xi[0] + xi[1] + xi[2] + v[i][0] + v[i][1] + v[i][2] + f[i][0] + f[i][1] + f[i][2];
    if (!std::isfinite(sum)) {
      one[0] = std::max(one[0], -(double) tag[i]);
      continue;
    }
    if (anypbc) {
      // fractional coordinates: Domain::pbc() can bring back atoms within [-1, 2)
      const double d0 = xi[0] - lo[0], d1 = xi[1] - lo[1], d2 = xi[2] - lo[2];
      const double l[3] = {hinv[0] * d0 + hinv[5] * d1 + hinv[4] * d2, hinv[1] * d1 + hinv[3] * d2,
                           hinv[2] * d2};
      for (int d = 0; d < 3; d++)
        if (pbc[d] && (l[d] < -1.0 || l[d] >= 2.0)) one[1] = std::max(one[1], -(double) tag[i]);
    }
    for (int d = 0; d < 3; d++) {
      one[2 + d] = std::max(one[2 + d], -xi[d]);
      one[5 + d] = std::max(one[5 + d], xi[d]);
    }
  }
  MPI_Allreduce(one, all, 8, MPI_DOUBLE, MPI_MAX, world);

  // neighbor bins LAMMPS will need if it rebuilds its lists now: the box of a non-periodic
  // dimension is reset to the atoms (shrink-wrapped) or stays fixed (atoms beyond a fixed
  // boundary are lost, an error of LAMMPS); bins of the default size, half the neighbor
  // cutoff, over the box plus the ghost cutoff at both ends

  double span[3], bins = 1.0;
  const double binsize = neighbor->binsizeflag ? neighbor->binsize_user
                                               : 0.5 * neighbor->cutneighmax;
  for (int d = 0; d < 3; d++) {
    double blo = domain->boxlo[d], bhi = domain->boxhi[d];
    if (!pbc[d] && all[5 + d] > NONE) {
      // s: the atoms' extent; m: at least the box it has now (LAMMPS: the initial box)
      if (domain->boundary[d][0] == 2) blo = -all[2 + d];
      if (domain->boundary[d][0] == 3) blo = std::min(blo, -all[2 + d]);
      if (domain->boundary[d][1] == 2) bhi = all[5 + d];
      if (domain->boundary[d][1] == 3) bhi = std::max(bhi, all[5 + d]);
    }
    span[d] = bhi - blo;
    if (binsize > 0.0) bins *= (span[d] + 2.0 * comm->cutghost[d]) / binsize + 4.0;
  }
  constexpr double MAXBINS = 1073741824.0;    // 2^30: half of what LAMMPS can index
  const int which = (all[0] > NONE) ? 1 : (all[1] > NONE) ? 2 : (bins > MAXBINS) ? 3 : 0;
  if (!which) return;

  // the worst atom: the smallest ID for the first two kinds, else the one farthest outside
  // the box of the last neighbor list build (smallest ID among equals)

  tagint worst = 0;
  if (which < 3) {
    worst = (tagint) (-all[which - 1]);
  } else {
    double far = -1.0;
    tagint id = 0;
    for (int i = 0; i < nlocal; i++) {
      double out = 0.0;
      for (int d = 0; d < 3; d++)
        out = std::max(out, std::max(domain->boxlo[d] - x[i][d], x[i][d] - domain->boxhi[d]));
      if (out > far || (out == far && tag[i] < id)) {
        far = out;
        id = tag[i];
      }
    }
    double farall;
    MPI_Allreduce(&far, &farall, 1, MPI_DOUBLE, MPI_MAX, world);
    tagint mine = (far == farall) ? id : std::numeric_limits<tagint>::max();
    MPI_Allreduce(&mine, &worst, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  }

  // what the owner of that atom knows (position, velocity, which values are not finite)

  double det[7] = {NONE, NONE, NONE, NONE, NONE, NONE, NONE}, detall[7];
  for (int i = 0; i < nlocal; i++) {
    if (tag[i] != worst) continue;
    int bad = 0;
    for (int d = 0; d < 3; d++) {
      if (!std::isfinite(x[i][d])) bad |= 1;
      if (!std::isfinite(v[i][d])) bad |= 2;
      if (!std::isfinite(f[i][d])) bad |= 4;
    }
    det[6] = bad;
    for (int d = 0; d < 3; d++) {
      det[d] = (bad & 1) ? 0.0 : x[i][d];
      det[3 + d] = (bad & 2) ? 0.0 : v[i][d];
    }
  }
  MPI_Allreduce(det, detall, 7, MPI_DOUBLE, MPI_MAX, world);
  const double speed = sqrt(detall[3] * detall[3] + detall[4] * detall[4] + detall[5] * detall[5]);

  const std::string cause = likely_cause(converged);
  const bigint step = update->ntimestep;
  if (which == 1) {
    const int bad = (int) detall[6];
    std::vector<std::string> names;
    if (bad & 1) names.emplace_back("position");
    if (bad & 2) names.emplace_back("velocity");
    if (bad & 4) names.emplace_back("force");
    std::string what;
    for (size_t k = 0; k < names.size(); k++)
      what += (k == 0 ? "" : (k + 1 == names.size() ? " and " : ", ")) + names[k];
    error->all(FLERR,
               "Pair peri/nosb: the run is unstable: at step {} atom {} has a non-finite {}; "
               "likely cause: {}",
               step, worst, what, cause);
  } else if (which == 2) {
    error->all(FLERR,
               "Pair peri/nosb: the run is unstable: at step {} atom {} is at ({:.4g}, {:.4g}, "
               "{:.4g}), more than one box length outside the periodic box (speed {:.4g}, "
               "{:.4g} per step); likely cause: {}",
               step, worst, detall[0], detall[1], detall[2], speed, speed * update->dt, cause);
  } else {
    error->all(FLERR,
               "Pair peri/nosb: the run is unstable: at step {} the atoms span {:.4g} x {:.4g} x "
               "{:.4g}, too far for LAMMPS's neighbor bins; atom {} is farthest from the box of "
               "the last neighbor list build, at ({:.4g}, {:.4g}, {:.4g}), speed {:.4g} "
               "({:.4g} per step); likely cause: {}",
               step, span[0], span[1], span[2], worst, detall[0], detall[1], detall[2], speed,
               speed * update->dt, cause);
  }
}

/* ----------------------------------------------------------------------
   the likely cause of a blow-up (all ranks), from the integrator and the time step
------------------------------------------------------------------------- */

std::string FixNosbFamily::likely_cause(int converged)
{
  const double dt = update->dt;
  const double est = min_stable_time_step();
  if (converged == 0)
    return fmt::format("fix sissm stopped at its iteration limit without converging, at time "
                       "step dt = {:.4g} ({:.3g} x the estimated explicit stable time step {:.4g} "
                       "of peri/nosb): lower the time step or raise its iterations{}",
                       dt, dt / est, est,
                       dt <= est ? "; with a time step this small, check the initial velocities "
                                   "and external forces as well"
                                 : "");
  if (converged == 1)
    return fmt::format("fix sissm converged in this step (dt = {:.4g}), so the motion was put in "
                       "from outside: check initial velocities and positions (velocity, set, "
                       "displace_atoms) and fixes that add forces",
                       dt);
  if (dt > est)
    return fmt::format("time step dt = {:.4g} is above the estimated stable time step {:.4g} "
                       "of peri/nosb (compute nosb/atom column 11, formula in the pair_style "
                       "peri/nosb doc)",
                       dt, est);
  return fmt::format("time step dt = {:.4g} is within the estimated stable time step {:.4g} of "
                     "peri/nosb at rest (compute nosb/atom column 11): either the body is "
                     "deformed far from rest (strongly compressed or inverted particles are "
                     "stiffer: lower the time step), or the motion was put in from outside "
                     "(check initial velocities and positions: velocity, set, displace_atoms; "
                     "and fixes that add forces)",
                     dt, est);
}
