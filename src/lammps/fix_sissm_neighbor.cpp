/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm, neighbor list builds inside a cut-back step (doc/fix_sissm.rst,
   "Contact"). A step that moves atoms farther than the contact candidates of the last build can
   follow does not converge (its iterates are incomplete) and is cut back into sub-steps; each
   sub-step that starts far from the last build starts from a new one, made here as LAMMPS's
   integrators make it between steps (periodic wrap, migration to the owning rank, ghosts, the
   list, the fixes' pre/post_neighbor), with the step's per-atom rows carried to the atoms'
   new local indices and ranks (core solvers/carried_rows.h).
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "collision_limit.h"
#include "fix_sissm_system.h"
#include "implicit_forces.h"

#include "solvers/carried_rows.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "modify.h"
#include "neighbor.h"

#include <vector>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   before a sub-step (all ranks): a neighbor list build when the short-range contact of the
   pair or a contact fix asks for one at the current positions
------------------------------------------------------------------------- */

void FixSissm::start_substep()
{
  bool wanted = forces->contact_build_wanted() > 0;
  for (CollisionLimit *limit : limiters) wanted = limit->rebuild_wanted(false) || wanted;
  if (wanted) build_neighbors_in_step();
}

/* ----------------------------------------------------------------------
   the last solve ended beyond the reach of the pair's contact candidates, or its end was cut
   short by the reach of a contact fix's candidates (all ranks)
------------------------------------------------------------------------- */

bool FixSissm::beyond_reach()
{
  return end_reach || forces->contact_build_wanted() == 2;
}

/* ----------------------------------------------------------------------
   a neighbor list build in the middle of the step, as Verlet makes one between steps without
   the pre_exchange of other fixes (which add or remove atoms at their own steps) and without
   sorting; the rows of atoms that changed ranks are sent to all ranks, each takes its own
------------------------------------------------------------------------- */

void FixSissm::build_neighbors_in_step()
{
  std::vector<std::int64_t> ids(atom->tag, atom->tag + atom->nlocal);
  PeriSISSM::CarriedRows carried(carried_arrays());
  carried.pack(atom->nlocal, ids.data(), atom->x);

  if (domain->triclinic) domain->x2lamda(atom->nlocal);
  domain->pbc();
  if (domain->box_change) {
    domain->reset_box();
    comm->setup();
    if (neighbor->style) neighbor->setup_bins();
  }
  comm->exchange();
  comm->borders();
  if (domain->triclinic) domain->lamda2x(atom->nlocal + atom->nghost);
  if (modify->n_pre_neighbor) modify->pre_neighbor();
  neighbor->build(1);
  if (modify->n_post_neighbor) modify->post_neighbor();

  // the rows of the atoms that left this rank, from every rank to every rank
  const int nlocal = atom->nlocal;
  std::vector<double> sent = carried.departed([&](std::int64_t id) {
    const int i = atom->map((tagint) id);
    return i >= 0 && i < nlocal;
  });
  int mine = (int) sent.size();
  std::vector<int> counts(comm->nprocs), displs(comm->nprocs, 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int p = 1; p < comm->nprocs; p++) displs[p] = displs[p - 1] + counts[p - 1];
  std::vector<double> arrived((std::size_t) displs.back() + counts.back());
  MPI_Allgatherv(sent.data(), mine, MPI_DOUBLE, arrived.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);

  grow();
  ids.assign(atom->tag, atom->tag + nlocal);
  carried.set_arrays(carried_arrays());
  const int lost = carried.unpack(nlocal, ids.data(), atom->x, arrived);
  if (lost >= 0)
    error->one(FLERR, "Fix sissm {}: atom {} has no step data after a neighbor list build", id,
               atom->tag[lost]);
  // the rows of the system, as at the start of the step
  system->step_rows() = {nlocal, atom->mask, groupbit, atom->vfrac, atom->rmass, psize};
}
