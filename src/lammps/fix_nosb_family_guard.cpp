/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/family: the stable time step estimate (core peri/stable_step.h) and the blow-up
   guard (doc/pair_peri_nosb.rst, "Blow-ups end in an error"; arithmetic and message text in
   core peri/blowup_guard.h).
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
#include <limits>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   stable time steps over the current bonds (broken ones do not count) in the reference state:
   they change only when bonds break
------------------------------------------------------------------------- */

void FixNosbFamily::stable_time_steps(double *dt)
{
  const int nlocal = atom->nlocal;
  if (!built) {
    std::fill(dt, dt + nlocal, std::numeric_limits<double>::infinity());
    return;
  }
  if (atom->nmax > 0 && !sdiag) grow_arrays(atom->nmax);
  PeriSISSM::stable_step_stiffnesses(*model, nlocal, atom->type, kinv, kregular, sdiag);
  comm->forward_comm(this);

  // partners through the atom map (any image carries s_j), so that this also works between
  // runs, when jlocal may be stale
  const auto locate = [&](tagint id) {
    return local_index(id);
  };
  PeriSISSM::stable_time_steps(nlocal, atom->rmass, npartner, partner, omega, sdiag, locate, dt);
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

/* ---------------------------------------------------------------------- */

void FixNosbFamily::check_motion(int converged)
{
  if (converged >= 0) integrator_checks = 1;

  // the neighbor bins LAMMPS will need if it rebuilds its lists now are of the default size,
  // half the neighbor cutoff

  const double binsize = neighbor->binsizeflag ? neighbor->binsize_user
                                               : 0.5 * neighbor->cutneighmax;
  const PeriSISSM::GuardBox frame = {{domain->boxlo, domain->h_inv, domain->periodicity},
                                     domain->boxhi,
                                     domain->boundary,
                                     comm->cutghost,
                                     binsize};
  const auto reduce_max = [&](double *buf, int n) {
    MPI_Allreduce(MPI_IN_PLACE, buf, n, MPI_DOUBLE, MPI_MAX, world);
  };
  tagint worst = 0;
  double rec[7], span[3];
  const int which = PeriSISSM::guard_motion(atom->nlocal, atom->x[0], atom->v[0], atom->f[0],
                                            atom->tag, frame, reduce_max, worst, rec, span);
  if (!which) return;

  const std::string cause = PeriSISSM::likely_cause(converged, update->dt, min_stable_time_step());
  error->all(
      FLERR,
      PeriSISSM::blowup_message(which, update->ntimestep, worst, rec, span, update->dt, cause));
}
