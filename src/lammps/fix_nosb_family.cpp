/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/family: the bond families of pair_style peri/nosb (doc/pair_peri_nosb.rst, "Bond
   families and reference configuration"; what is stored: fix_nosb_family.h). The LAMMPS-free
   parts: core peri/family_build.h (partners, weights), peri/family_ids.h (partners by ID),
   peri/family_records.h (exchange and restart records), peri/family_messages.h (texts).
   Blow-up guard and stable time step: fix_nosb_family_guard.cpp.
------------------------------------------------------------------------- */

#include "fix_nosb_family.h"

#include "mesh_view.h"
#include "restart_records.h"

#include "peri/family_build.h"
#include "peri/family_ids.h"
#include "peri/family_messages.h"
#include "peri/family_records.h"
#include "peri/model.h"
#include "peri/stable_step.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixNosbFamily::FixNosbFamily(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), built(0), maxpartner(1), npartner(nullptr), partner(nullptr),
    omega(nullptr), kinv(nullptr), kregular(nullptr), vinit(nullptr), lamref(nullptr),
    owntag(nullptr), jlocal(nullptr), tagmax0(0), model(nullptr), list(nullptr), sdiag(nullptr),
    integrator_checks(0), dtstable0(0.0)
{
  if (narg != 3) error->all(FLERR, "Illegal fix nosb/family command: no arguments expected");

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = PeriSISSM::family_record_size(maxpartner);
  comm_forward = 1;    // sdiag (stable_time_steps)

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

/* ---------------------------------------------------------------------- */

FixNosbFamily::~FixNosbFamily()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);

  memory->destroy(npartner);
  memory->destroy(partner);
  memory->destroy(omega);
  memory->destroy(kinv);
  memory->destroy(kregular);
  memory->destroy(vinit);
  memory->destroy(lamref);
  memory->destroy(owntag);
  memory->destroy(jlocal);
  memory->destroy(sdiag);
}

/* ---------------------------------------------------------------------- */

int FixNosbFamily::setmask()
{
  return POST_NEIGHBOR | MIN_POST_NEIGHBOR | POST_INTEGRATE;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::init()
{
  if (!model || !force->pair_match("peri/nosb", 1))
    error->all(FLERR,
               "Fix nosb/family requires pair_style peri/nosb (it is created by that "
               "pair style and is not meant to be defined in an input script)");

  // a full neighbor list once, to build the families. LAMMPS (4Feb2025) makes a list a
  // trimmed copy of a longer one (fix nosb/contact's) and NPairTrim trims a list without a
  // custom cutoff at distance 0: every atom was left without a bond. So when the user's ghost
  // cutoff (comm_modify cutoff, which a longer list needs) exceeds the default list cutoff, the
  // list gets a custom cutoff of its own, just above the default one (LAMMPS keeps a custom
  // cutoff only above its shortest list cutoff): trimmed at it, or built alone, never emptied.
  // (With the ghost cutoff itself as that cutoff, stacked cloths with a wide contact skin held
  // more than LAMMPS's 2000 neighbors per atom in this list.) The families keep the horizon and
  // are ordered by ID, whichever list they come from.

  if (!built) {
    auto req = neighbor->add_request(this, NeighConst::REQ_FULL | NeighConst::REQ_OCCASIONAL);
    const double cutdefault = force->pair->cutforce + neighbor->skin;
    if (comm->cutghostuser > cutdefault) req->set_cutoff(cutdefault * (1.0 + 1.0e-6));
  }

  // an implicit integrator moves the atoms in its own post_integrate, which may come after
  // this one, and calls check_motion() itself once it has (through the pair's ImplicitForces);
  // from its first call of a run on, the check of post_integrate is left to it

  integrator_checks = 0;

  // PD scale factor used by dump cfg, as set by the built-in PERI styles

  double vone = 0.0;
  for (int i = 0; i < atom->nlocal; i++) vone += atom->vfrac[i];
  double vave;
  MPI_Allreduce(&vone, &vave, 1, MPI_DOUBLE, MPI_SUM, world);
  if (atom->natoms) vave /= atom->natoms;
  atom->pdscale = (vave > 0.0) ? 1.44 / cbrt(vave) : 1.0;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::init_list(int /*id*/, NeighList *ptr)
{
  list = ptr;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::setup_post_neighbor()
{
  if (!built) build_families();
  refresh_local_indices();
  dtstable0 = min_stable_time_step();
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::post_neighbor()
{
  refresh_local_indices();
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::min_post_neighbor()
{
  refresh_local_indices();
}

/* ----------------------------------------------------------------------
   build the families from the current positions (reference configuration)
------------------------------------------------------------------------- */

void FixNosbFamily::build_families()
{
  double **x = atom->x;
  int *type = atom->type;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  neighbor->build_one(list);

  // partners of each owned atom (core peri/family_build.h): mesh vertices only within their
  // own mesh; membranes take their weights from their thickness

  MeshView *meshfix = MeshView::find(lmp);
  const int *mesh = meshfix ? meshfix->mesh_ids() : nullptr;
  const double *thick = meshfix ? meshfix->thicknesses() : nullptr;
  std::vector<std::vector<std::pair<tagint, int>>> fam(nlocal);
  int maxone = 0;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    PeriSISSM::gather_partners(*model, i, list->firstneigh[i], list->numneigh[i], NEIGHMASK, x[0],
                               type, tag, mesh, fam[i]);
    const tagint twice = PeriSISSM::order_family(fam[i]);
    if (twice) error->one(FLERR, PeriSISSM::partner_twice_message(twice, tag[i]));
    maxone = std::max(maxone, (int) fam[i].size());
  }
  MPI_Allreduce(&maxone, &maxpartner, 1, MPI_INT, MPI_MAX, world);
  maxpartner = std::max(maxpartner, 1);
  resize_bond_slots();

  // the reference configuration is the current one, in the current box; the reference
  // normals of the membranes from the mesh in it

  const int tri = domain->triclinic;
  box = {{domain->xperiodic, domain->yperiodic, domain->zperiodic},
         {domain->xprd, domain->yprd, domain->zprd, tri ? domain->yz : 0.0, tri ? domain->xz : 0.0,
          tri ? domain->xy : 0.0}};
  std::copy(x[0], x[0] + 3 * (nlocal + atom->nghost), atom->x0[0]);
  if (meshfix && model->any_membrane()) meshfix->set_reference_normals();

  bigint one[2] = {0, 0}, all[2];
  const std::pair<int, int> same = PeriSISSM::store_families(
      *model, rows(), view(), fam, tag, atom->x0[0], box, type, atom->vfrac, thick, one[0], one[1]);
  if (same.first >= 0)
    error->one(FLERR, PeriSISSM::same_position_message(tag[same.first], tag[same.second]));
  built = 1;

  tagint tagmax = 0;
  for (int i = 0; i < nlocal; i++) tagmax = std::max(tagmax, tag[i]);
  MPI_Allreduce(&tagmax, &tagmax0, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  MPI_Allreduce(one, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me == 0) utils::logmesg(lmp, PeriSISSM::family_summary(all[0], atom->natoms, all[1]));
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::attach(const PeriSISSM::Model *m, std::function<void()> rebuilt)
{
  model = m;
  neighbor_rebuilt = std::move(rebuilt);
}

/* ---------------------------------------------------------------------- */

PeriSISSM::Families FixNosbFamily::view()
{
  MeshView *meshfix = (model && model->any_membrane()) ? MeshView::find(lmp) : nullptr;
  return {npartner,
          jlocal,
          omega,
          kinv,
          kregular,
          lamref,
          meshfix ? meshfix->reference_normals() : nullptr};
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::forget_broken(const std::vector<int> &atoms)
{
  for (int i : atoms)
    for (int b = 0; b < npartner[i]; b++)
      if (jlocal[i][b] < 0) partner[i][b] = 0;
}

/* ---------------------------------------------------------------------- */

double FixNosbFamily::damage(int i) const
{
  return PeriSISSM::damage(npartner[i], partner[i], omega[i], vinit[i]);
}

/* ----------------------------------------------------------------------
   local indices of the partners of all owned atoms: closest image of each partner
   (bookkeeping by ID: core peri/family_ids.h)
------------------------------------------------------------------------- */

void FixNosbFamily::refresh_local_indices()
{
  if (neighbor_rebuilt) neighbor_rebuilt();
  if (!built) return;
  const int nlocal = atom->nlocal;
  const PeriSISSM::FamilyArrays<tagint> a = rows();

  // families refer to atom IDs: renumbered IDs would silently pair the wrong atoms, and so
  // would an ID of a deleted atom that create_atoms gave to a new one

  std::vector<tagint> reused;
  int flags[2] = {PeriSISSM::adopt_ids(a, nlocal, atom->tag, tagmax0, reused) ? 1 : 0, 0};
  flags[1] = (int) reused.size();
  int flags_all[2];
  MPI_Allreduce(flags, flags_all, 2, MPI_INT, MPI_MAX, world);
  if (flags_all[0]) error->all(FLERR, PeriSISSM::renumbered_message());
  if (flags_all[1]) break_reused(reused);

  std::vector<std::pair<int, int>> missing;    // (atom, slot) whose partner is not here
  PeriSISSM::locate_partners(
      a, nlocal,
      [&](int i, tagint jtag) {
        const int j = local_index(jtag);
        return j < 0 ? -1 : domain->closest_image(i, j);
      },
      missing);

  int nmissing = (int) missing.size(), nmissing_all;
  MPI_Allreduce(&nmissing, &nmissing_all, 1, MPI_INT, MPI_SUM, world);
  if (nmissing_all) resolve_missing(missing);

  const PeriSISSM::Families fview = view();
  for (int i : reshape)
    PeriSISSM::update_shape(fview, atom->x0[0], box, i,
                            model->reference_normal(fview, atom->type[i], i));
  reshape.clear();
}

/* ----------------------------------------------------------------------
   the tags of every rank, concatenated in rank order (the same vector on all ranks);
   offset (if given) receives where this rank's tags start in it
------------------------------------------------------------------------- */

std::vector<tagint> FixNosbFamily::allgather_tags(const std::vector<tagint> &mine, int *offset)
{
  const int nme = (int) mine.size();
  std::vector<int> counts(comm->nprocs), displs(comm->nprocs);
  MPI_Allgather(&nme, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int ntotal = 0;
  for (int p = 0; p < comm->nprocs; p++) {
    displs[p] = ntotal;
    ntotal += counts[p];
  }
  std::vector<tagint> all(ntotal);
  MPI_Allgatherv(mine.data(), nme, MPI_LMP_TAGINT, all.data(), counts.data(), displs.data(),
                 MPI_LMP_TAGINT, world);
  if (offset) *offset = displs[comm->me];
  return all;
}

/* ----------------------------------------------------------------------
   new atoms that got the ID of a deleted bond partner: those bonds are broken
------------------------------------------------------------------------- */

void FixNosbFamily::break_reused(const std::vector<tagint> &reused)
{
  std::vector<tagint> all = allgather_tags(reused);
  std::sort(all.begin(), all.end());
  int nbroken = PeriSISSM::break_bonds_to(rows(), atom->nlocal, all, reshape), nbroken_all;
  MPI_Allreduce(&nbroken, &nbroken_all, 1, MPI_INT, MPI_SUM, world);
  if (comm->me == 0 && nbroken_all)
    error->warning(FLERR, PeriSISSM::reused_ids_message(all.size(), nbroken_all));
}

/* ----------------------------------------------------------------------
   partners that are neither local nor ghost atoms: a partner that no longer exists
   anywhere (delete_atoms, lost atoms) counts as a broken bond; a partner that exists on
   another rank beyond the ghost cutoff is an error
------------------------------------------------------------------------- */

void FixNosbFamily::resolve_missing(const std::vector<std::pair<int, int>> &missing)
{
  const int nme = (int) missing.size();
  std::vector<tagint> mine(nme);
  for (int k = 0; k < nme; k++) mine[k] = partner[missing[k].first][missing[k].second];
  int first = 0;
  const std::vector<tagint> all = allgather_tags(mine, &first);

  // which of the wanted tags are owned somewhere

  std::vector<int> own(all.size(), 0), exists(all.size(), 0);
  for (size_t k = 0; k < all.size(); k++) {
    const int j = local_index(all[k]);
    if (j >= 0 && j < atom->nlocal) own[k] = 1;
  }
  MPI_Allreduce(own.data(), exists.data(), (int) all.size(), MPI_INT, MPI_MAX, world);
  for (int k = 0; k < nme; k++) {
    if (!exists[first + k]) continue;
    error->one(FLERR,
               "Pair peri/nosb: bond partner atom {} of atom {} is neither a local nor a ghost "
               "atom on this MPI rank at step {}: the bond is longer than the ghost cutoff {}; "
               "increase it with comm_modify cutoff (or the neighbor skin), unless the body is "
               "flying apart: time step dt = {:.4g}, estimated stable time step of peri/nosb "
               "{:.4g} at the start of the run (compute nosb/atom column 11)",
               all[first + k], atom->tag[missing[k].first], update->ntimestep,
               comm->get_comm_cutoff(), update->dt, dtstable0);
  }
  PeriSISSM::break_missing(rows(), missing, reshape);

  int nbroken_all;
  MPI_Allreduce(&nme, &nbroken_all, 1, MPI_INT, MPI_SUM, world);
  if (comm->me == 0) error->warning(FLERR, PeriSISSM::lost_partners_message(nbroken_all));
}

/* ----------------------------------------------------------------------
   atom->map() with a guard: the map is only valid up to the largest current atom ID
   (entries of deleted atoms with larger IDs are stale)
------------------------------------------------------------------------- */

int FixNosbFamily::local_index(tagint jtag) const
{
  if (jtag <= 0 || jtag > atom->map_tag_max) return -1;
  return atom->map(jtag);
}

/* ---------------------------------------------------------------------- */

double FixNosbFamily::memory_usage()
{
  const double nmax = atom->nmax;
  double bytes = nmax * (2.0 * sizeof(int) + sizeof(tagint) + 13.0 * sizeof(double));
  bytes += nmax * maxpartner * (sizeof(tagint) + sizeof(int) + sizeof(double));
  return bytes;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::grow_arrays(int nmax)
{
  memory->grow(npartner, nmax, "nosb/family:npartner");
  memory->grow(partner, nmax, maxpartner, "nosb/family:partner");
  memory->grow(omega, nmax, maxpartner, "nosb/family:omega");
  memory->grow(kinv, nmax, 9, "nosb/family:kinv");
  memory->grow(kregular, nmax, "nosb/family:kregular");
  memory->grow(vinit, nmax, "nosb/family:vinit");
  memory->grow(lamref, nmax, "nosb/family:lamref");
  memory->grow(owntag, nmax, "nosb/family:owntag");
  memory->grow(jlocal, nmax, maxpartner, "nosb/family:jlocal");
  memory->grow(sdiag, nmax, "nosb/family:sdiag");
}

/* ----------------------------------------------------------------------
   the per-atom arrays as the core's records see them (core peri/family_records.h); an atom
   created after the families exist has no bonds
------------------------------------------------------------------------- */

PeriSISSM::FamilyArrays<tagint> FixNosbFamily::rows() const
{
  return {npartner, partner, omega, jlocal, kinv, kregular, vinit, lamref, owntag};
}

void FixNosbFamily::copy_arrays(int i, int j, int /*delflag*/)
{
  PeriSISSM::copy_family(rows(), i, j);
}

void FixNosbFamily::set_arrays(int i)
{
  PeriSISSM::clear_family(rows(), i);
}

int FixNosbFamily::pack_exchange(int i, double *buf)
{
  return PeriSISSM::pack_family(rows(), i, buf);
}

int FixNosbFamily::unpack_exchange(int nlocal, double *buf)
{
  return PeriSISSM::unpack_family(rows(), nlocal, buf);
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::write_restart(FILE *fp)
{
  double list[PeriSISSM::kFamilyGlobals];
  PeriSISSM::pack_family_globals(built, maxpartner, box, tagmax0, list);
  write_global_record(fp, comm->me, list, PeriSISSM::kFamilyGlobals);
}

/* ----------------------------------------------------------------------
   a file of another format version is refused before its per-atom data are read
------------------------------------------------------------------------- */

void FixNosbFamily::restart(char *buf)
{
  auto list = (double *) buf;
  if (!PeriSISSM::unpack_family_globals(list, built, maxpartner, box, tagmax0))
    error->all(FLERR,
               "Pair peri/nosb: the restart file holds bond families of another format version "
               "({} instead of {}): write the restart file again with this build (or use the "
               "build that wrote it)",
               list[0], PeriSISSM::kFamilyRestartVersion);
  resize_bond_slots();    // before per-atom data arrive
}

/* ----------------------------------------------------------------------
   maxpartner changed: the exchange record's size and the second dimension of the per-bond
   arrays follow it (those are reallocated, their contents are not kept)
------------------------------------------------------------------------- */

void FixNosbFamily::resize_bond_slots()
{
  maxexchange = PeriSISSM::family_record_size(maxpartner);
  memory->destroy(partner);
  memory->destroy(omega);
  memory->destroy(jlocal);
  grow_arrays(atom->nmax);
}

/* ----------------------------------------------------------------------
   per-atom restart data: size first (as other fixes expect), then as in pack_exchange
------------------------------------------------------------------------- */

int FixNosbFamily::pack_restart(int i, double *buf)
{
  return pack_sized_record(buf, [&](double *rec) {
    return pack_exchange(i, rec);
  });
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::unpack_restart(int nlocal, int nth)
{
  unpack_exchange(nlocal, fix_record(atom->extra, nlocal, nth) + 1);
}

/* ---------------------------------------------------------------------- */

int FixNosbFamily::maxsize_restart()
{
  return 1 + PeriSISSM::family_record_size(maxpartner);
}

int FixNosbFamily::size_restart(int i)
{
  return 1 + PeriSISSM::family_record_size(PeriSISSM::unbroken_bonds(rows(), i));
}

/* ---------------------------------------------------------------------- */

int FixNosbFamily::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  for (int k = 0; k < n; k++) buf[k] = sdiag[list[k]];
  return n;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::unpack_forward_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) sdiag[first + k] = buf[k];
}
