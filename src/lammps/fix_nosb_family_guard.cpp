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
   step against the estimate of stable_time_steps(); its arithmetic is core
   peri/blowup_guard.h. Cost: one pass over the owned atoms and one MPI_Allreduce of 8 doubles
   per step.
------------------------------------------------------------------------- */

#include "fix_nosb_family.h"

#include "peri/blowup_guard.h"
#include "peri/model.h"
#include "peri/stable_step.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
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

  // partners through the atom map (any image carries s_j), so that this also works between
  // runs, when jlocal may be stale
  const auto locate = [&](tagint id) {
    return local_index(id);
  };
  for (int i = 0; i < nlocal; i++) {
    const double d = built
        ? PeriSISSM::stable_step_coupling(npartner[i], partner[i], omega[i], sdiag, i, locate)
        : 0.0;
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

  // the scan (core peri/blowup_guard.h) reduced over all ranks, and the neighbor bins LAMMPS
  // will need if it rebuilds its lists now (bins of the default size, half the neighbor cutoff)

  double one[PeriSISSM::kGuardScan], all[PeriSISSM::kGuardScan];
  PeriSISSM::clear_guard_scan(one);
  const PeriSISSM::PeriodicCell cell = {domain->boxlo, domain->h_inv, domain->periodicity};
  for (int i = 0; i < nlocal; i++)
    PeriSISSM::scan_atom_motion(x[i], v[i], f[i], (double) tag[i], cell, one);
  MPI_Allreduce(one, all, PeriSISSM::kGuardScan, MPI_DOUBLE, MPI_MAX, world);

  double span[3];
  const double binsize = neighbor->binsizeflag ? neighbor->binsize_user
                                               : 0.5 * neighbor->cutneighmax;
  const double bins =
      PeriSISSM::neighbor_bins(domain->boxlo, domain->boxhi, domain->boundary, domain->periodicity,
                               comm->cutghost, binsize, all, span);
  const int which = PeriSISSM::blowup_kind(all, bins);
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
      const double out = PeriSISSM::distance_outside(x[i], domain->boxlo, domain->boxhi);
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

  double det[7], detall[7];
  std::fill(det, det + 7, PeriSISSM::kGuardNone);
  for (int i = 0; i < nlocal; i++)
    if (tag[i] == worst) PeriSISSM::worst_atom_record(x[i], v[i], f[i], det);
  MPI_Allreduce(det, detall, 7, MPI_DOUBLE, MPI_MAX, world);
  const double speed = sqrt(detall[3] * detall[3] + detall[4] * detall[4] + detall[5] * detall[5]);

  const std::string cause = likely_cause(converged);
  const bigint step = update->ntimestep;
  if (which == 1) {
    error->all(FLERR,
               "Pair peri/nosb: the run is unstable: at step {} atom {} has a non-finite {}; "
               "likely cause: {}",
               step, worst, PeriSISSM::nonfinite_names((int) detall[6]), cause);
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
