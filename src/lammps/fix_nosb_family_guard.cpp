/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/family: the stable time step estimate (core peri/stable_step.h), its check at the
   setup of explicit runs (core peri/step_check.h) and the blow-up guard (doc/pair_peri_nosb.rst,
   "Blow-ups end in an error"; arithmetic and message text in core peri/blowup_guard.h).
------------------------------------------------------------------------- */

#include "fix_nosb_family.h"

#include "pair_peri_nosb.h"

#include "peri/blowup_guard.h"
#include "peri/model.h"
#include "peri/stable_step.h"
#include "peri/step_check.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
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

/* ----------------------------------------------------------------------
   at the setup of every run (not of minimizations): one warning when the time step is above
   the estimate (compute nosb/atom column 11: with the bending hinges) of any particle that a
   fix integrates explicitly (core peri/step_check.h explicit_integrator); nothing is computed
   in a run without such a fix
------------------------------------------------------------------------- */

void FixNosbFamily::setup(int /*vflag*/)
{
  if (!built) return;
  int bits = 0;
  std::string fixes;
  for (Fix *f : modify->get_fix_list()) {
    if (!f->time_integrate || !PeriSISSM::explicit_integrator(f->style)) continue;
    bits |= f->groupbit;
    fixes += (fixes.empty() ? "" : ", ") + std::string(f->id) + " (" + f->style + ")";
  }
  if (!bits) return;

  const int nlocal = atom->nlocal;
  std::vector<double> dt(nlocal);
  // (init has checked that the pair style is peri/nosb: this fix is its family)
  static_cast<PairPeriNosb *>(force->pair_match("peri/nosb", 1))->stable_time_steps(dt.data());
  const PeriSISSM::StepExcess one =
      PeriSISSM::step_excess(nlocal, dt.data(), atom->mask, bits, update->dt);
  double smallest;
  bigint counts[2] = {one.above, one.counted}, all[2];
  MPI_Allreduce(&one.smallest, &smallest, 1, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(counts, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all[0] > 0 && comm->me == 0)
    error->warning(FLERR, PeriSISSM::step_warning(update->dt, smallest, all[0], all[1], fixes));
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
