/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/family: the bond families of pair_style peri/nosb.

   Families are built once, at the setup of the first run or minimization after the pair style
   is defined (after the neighbor list build, before the first force evaluation, so step 0
   already has the right energy): partner j is in the family of i when |x_j - x_i| <= horizon
   of their types, with the positions at that moment taken as the reference configuration
   (x0 = x for every atom). Families are stored by atom tag and sorted by tag, so that every
   per-particle sum runs in the same order whatever the number of MPI ranks. A broken bond has
   tag 0 and stays broken; broken slots are dropped when the atom migrates. Per bond the fix
   keeps the weight omega = w beta V_j (pair peri/nosb); the reference bond xi = X_j - X_i is
   x0_j - x0_i (minimum image in the box of the creation). Per atom: K^-1 (zeros if
   singular), the regular flag, the initial family weight (damage reference), the largest
   eigenvalue of the initial K (singularity test) and the atom's own ID. Everything migrates
   with the atoms and is kept in restart files. Local indices of the partners (closest image)
   are refreshed after every neighbor list build; a partner that no longer exists (deleted or
   lost atom) counts as a broken bond, one that exists beyond the ghost cutoff is an error.

   Blow-up guard and stable time step: fix_nosb_family_guard.cpp.
------------------------------------------------------------------------- */

#include "fix_nosb_family.h"

#include "mesh_view.h"

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
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

// per-atom doubles after the bonds in exchange and restart buffers:
// K^-1, regular, vinit, lamref, owntag
static constexpr int NATOMDATA = 13;
// doubles per bond in exchange and restart buffers: partner tag, omega
static constexpr int NBONDDATA = 2;
// global restart data: format version, built, maxpartner, periodic (3), box0 (6), tagmax0
static constexpr int NGLOBAL = 13;
// format of the restart data (global and per atom); 2: the first one with a version
static constexpr int RESTART_VERSION = 2;

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
  maxexchange = 1 + NATOMDATA + NBONDDATA * maxpartner;
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
  // list gets that cutoff as its own: trimmed at it, or built alone, never emptied. A longer
  // list than the horizon costs nothing but its one build: the families keep the horizon.

  if (!built) {
    auto req = neighbor->add_request(this, NeighConst::REQ_FULL | NeighConst::REQ_OCCASIONAL);
    const double cutdefault = force->pair->cutforce + neighbor->skin;
    if (comm->cutghostuser > cutdefault) req->set_cutoff(comm->cutghostuser);
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
  double **x0 = atom->x0;
  double *vfrac = atom->vfrac;
  int *type = atom->type;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;

  neighbor->build_one(list);
  const int inum = list->inum;

  // mesh vertices are bonded only within their own mesh (separate layers, a cloth and the
  // body it lies on, are never bonded); membranes take their weights from their thickness
  MeshView *meshfix = MeshView::find(lmp);
  const int *mesh = meshfix ? meshfix->mesh_ids() : nullptr;
  const double *thick = meshfix ? meshfix->thicknesses() : nullptr;
  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  // partners of each owned atom: (tag, local index of the image found by the list)

  std::vector<std::vector<std::pair<tagint, int>>> fam(nlocal);
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int itype = type[i];
    int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (mesh && mesh[i] != mesh[j]) continue;
      const double dx = x[j][0] - x[i][0];
      const double dy = x[j][1] - x[i][1];
      const double dz = x[j][2] - x[i][2];
      const double delta = model->horizon(itype, type[j]);
      if (dx * dx + dy * dy + dz * dz <= delta * delta) fam[i].emplace_back(tag[j], j);
    }
    const tagint twice = PeriSISSM::order_family(fam[i]);
    if (twice)
      error->one(FLERR,
                 "Pair peri/nosb: atom {} appears twice in the bond family of atom {}: the "
                 "periodic box is shorter than two horizons",
                 twice, tag[i]);
  }

  int maxone = 0;
  for (int i = 0; i < nlocal; i++) maxone = std::max(maxone, (int) fam[i].size());
  MPI_Allreduce(&maxone, &maxpartner, 1, MPI_INT, MPI_MAX, world);
  maxpartner = std::max(maxpartner, 1);
  maxexchange = 1 + NATOMDATA + NBONDDATA * maxpartner;

  memory->destroy(partner);
  memory->destroy(omega);
  memory->destroy(jlocal);
  grow_arrays(atom->nmax);

  // the reference configuration is the current one, in the current box

  box.periodic[0] = domain->xperiodic;
  box.periodic[1] = domain->yperiodic;
  box.periodic[2] = domain->zperiodic;
  box.box[0] = domain->xprd;
  box.box[1] = domain->yprd;
  box.box[2] = domain->zprd;
  box.box[3] = domain->triclinic ? domain->yz : 0.0;
  box.box[4] = domain->triclinic ? domain->xz : 0.0;
  box.box[5] = domain->triclinic ? domain->xy : 0.0;
  for (int i = 0; i < nall; i++) {
    x0[i][0] = x[i][0];
    x0[i][1] = x[i][1];
    x0[i][2] = x[i][2];
  }

  // reference normals of the membranes, from the mesh in the reference configuration
  if (meshfix && model->any_membrane()) meshfix->set_reference_normals();
  const PeriSISSM::Families fview = view();

  bigint nbonds = 0, nsingular = 0;
  for (int i = 0; i < nlocal; i++) {
    const int itype = type[i];
    npartner[i] = (int) fam[i].size();
    vinit[i] = 0.0;
    for (int b = 0; b < npartner[i]; b++) {
      const int j = fam[i][b].second;
      double xi[3];
      PeriSISSM::reference_bond(x0[0], box, i, j, xi);
      const double r = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
      if (r == 0.0)
        error->one(FLERR, "Pair peri/nosb: atoms {} and {} are at the same position", tag[i],
                   tag[j]);
      omega[i][b] = thick
          ? model->bond_weight(r, itype, type[j], vfrac[i], vfrac[j], thick[i], thick[j])
          : model->bond_weight(r, itype, type[j], vfrac[i], vfrac[j]);
      partner[i][b] = fam[i][b].first;
      jlocal[i][b] = j;
      vinit[i] += omega[i][b];
    }
    lamref[i] = 0.0;
    owntag[i] = tag[i];
    PeriSISSM::update_shape(fview, x0[0], box, i, model->reference_normal(fview, itype, i));
    nbonds += npartner[i];
    if (!kregular[i]) nsingular++;
  }
  built = 1;

  tagint tagmax = 0;
  for (int i = 0; i < nlocal; i++) tagmax = std::max(tagmax, tag[i]);
  MPI_Allreduce(&tagmax, &tagmax0, 1, MPI_LMP_TAGINT, MPI_MAX, world);

  bigint all[2], one[2] = {nbonds, nsingular};
  MPI_Allreduce(one, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "Peridynamic bond families (peri/nosb):\n"
                   "  total # of bonds = {}\n  bonds/atom = {:.8g}\n"
                   "  atoms with a singular shape tensor = {}\n",
                   all[0], atom->natoms ? (double) all[0] / atom->natoms : 0.0, all[1]);
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
  PeriSISSM::Families fam;
  fam.npartner = npartner;
  fam.jlocal = jlocal;
  fam.omega = omega;
  fam.kinv = kinv;
  fam.kregular = kregular;
  fam.lamref = lamref;
  if (model && model->any_membrane()) {
    MeshView *meshfix = MeshView::find(lmp);
    if (meshfix) fam.normal = meshfix->reference_normals();
  }
  return fam;
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
------------------------------------------------------------------------- */

void FixNosbFamily::refresh_local_indices()
{
  if (neighbor_rebuilt) neighbor_rebuilt();
  if (!built) return;
  const int nlocal = atom->nlocal;
  tagint *tag = atom->tag;

  // families refer to atom IDs: renumbered IDs would silently pair the wrong atoms, and so
  // would an ID of a deleted atom that create_atoms gave to a new one

  int flags[2] = {0, 0}, flags_all[2];
  std::vector<tagint> reused;
  for (int i = 0; i < nlocal; i++) {
    if (owntag[i] == 0) {    // atom created after the families (no bonds of its own)
      owntag[i] = tag[i];
      if (tag[i] <= tagmax0) reused.push_back(tag[i]);
    }
    if (owntag[i] != tag[i]) flags[0] = 1;
  }
  flags[1] = (int) reused.size();
  MPI_Allreduce(flags, flags_all, 2, MPI_INT, MPI_MAX, world);
  if (flags_all[0])
    error->all(FLERR,
               "Pair peri/nosb: atom IDs changed after the bond families were built (bonds "
               "are stored by atom ID): use delete_atoms ... compress no, and do not "
               "renumber atoms (reset_atoms id) once a peri/nosb run has been done");
  if (flags_all[1]) break_reused(reused);

  std::vector<std::pair<int, int>> missing;    // (atom, slot) whose partner is not here
  for (int i = 0; i < nlocal; i++) {
    for (int b = 0; b < npartner[i]; b++) {
      const tagint jtag = partner[i][b];
      if (jtag == 0) {
        jlocal[i][b] = -1;
        continue;
      }
      const int j = local_index(jtag);
      if (j < 0) {
        jlocal[i][b] = -1;
        missing.emplace_back(i, b);
        continue;
      }
      jlocal[i][b] = domain->closest_image(i, j);
    }
  }

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
  const int ntotal = (int) all.size();
  std::sort(all.begin(), all.end());

  int nbroken = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    int broke = 0;
    for (int b = 0; b < npartner[i]; b++) {
      if (partner[i][b] && std::binary_search(all.begin(), all.end(), partner[i][b])) {
        partner[i][b] = 0;
        broke = 1;
        nbroken++;
      }
    }
    if (broke) reshape.push_back(i);
  }
  int nbroken_all;
  MPI_Allreduce(&nbroken, &nbroken_all, 1, MPI_INT, MPI_SUM, world);
  if (comm->me == 0 && nbroken_all)
    error->warning(FLERR,
                   "Pair peri/nosb: {} new atoms reuse IDs of deleted atoms; the {} bond ends "
                   "to those IDs count as broken",
                   ntotal, nbroken_all);
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
  const int ntotal = (int) all.size();

  // which of the wanted tags are owned somewhere

  std::vector<int> own(ntotal, 0), exists(ntotal, 0);
  for (int k = 0; k < ntotal; k++) {
    const int j = local_index(all[k]);
    if (j >= 0 && j < atom->nlocal) own[k] = 1;
  }
  MPI_Allreduce(own.data(), exists.data(), ntotal, MPI_INT, MPI_MAX, world);

  int nbroken = 0;
  for (int k = 0; k < nme; k++) {
    const int i = missing[k].first;
    if (exists[first + k]) missing_partner(i, all[first + k]);
    partner[i][missing[k].second] = 0;
    nbroken++;
  }
  for (int k = 0; k < nme; k++)
    if (k == 0 || missing[k].first != missing[k - 1].first) reshape.push_back(missing[k].first);

  int nbroken_all;
  MPI_Allreduce(&nbroken, &nbroken_all, 1, MPI_INT, MPI_SUM, world);
  if (comm->me == 0)
    error->warning(FLERR,
                   "Pair peri/nosb: {} bond ends lost their partner atom (deleted or lost); "
                   "those bonds count as broken",
                   nbroken_all);
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

void FixNosbFamily::missing_partner(int i, tagint jtag)
{
  error->one(FLERR,
             "Pair peri/nosb: bond partner atom {} of atom {} is neither a local nor a ghost "
             "atom on this MPI rank at step {}: the bond is longer than the ghost cutoff {}; "
             "increase it with comm_modify cutoff (or the neighbor skin), unless the body is "
             "flying apart: time step dt = {:.4g}, estimated stable time step of peri/nosb {:.4g} "
             "at the start of the run (compute nosb/atom column 11)",
             jtag, atom->tag[i], update->ntimestep, comm->get_comm_cutoff(), update->dt, dtstable0);
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

/* ---------------------------------------------------------------------- */

void FixNosbFamily::copy_arrays(int i, int j, int /*delflag*/)
{
  npartner[j] = npartner[i];
  for (int b = 0; b < npartner[i]; b++) {
    partner[j][b] = partner[i][b];
    omega[j][b] = omega[i][b];
    jlocal[j][b] = jlocal[i][b];
  }
  memcpy(kinv[j], kinv[i], sizeof(double) * 9);
  kregular[j] = kregular[i];
  vinit[j] = vinit[i];
  lamref[j] = lamref[i];
  owntag[j] = owntag[i];
}

/* ----------------------------------------------------------------------
   an atom created after the families exist has no bonds
------------------------------------------------------------------------- */

void FixNosbFamily::set_arrays(int i)
{
  npartner[i] = 0;
  for (int k = 0; k < 9; k++) kinv[i][k] = 0.0;
  kregular[i] = 0;
  vinit[i] = 0.0;
  lamref[i] = 0.0;
  owntag[i] = 0;
}

/* ----------------------------------------------------------------------
   pack unbroken bonds and per-atom data: n, n x (tag, omega), K^-1, regular, vinit, lamref,
   owntag
------------------------------------------------------------------------- */

int FixNosbFamily::pack_exchange(int i, double *buf)
{
  int m = 1, n = 0;
  for (int b = 0; b < npartner[i]; b++) {
    if (partner[i][b] == 0) continue;
    buf[m++] = ubuf(partner[i][b]).d;
    buf[m++] = omega[i][b];
    n++;
  }
  buf[0] = n;
  for (int k = 0; k < 9; k++) buf[m++] = kinv[i][k];
  buf[m++] = kregular[i];
  buf[m++] = vinit[i];
  buf[m++] = lamref[i];
  buf[m++] = ubuf(owntag[i]).d;
  return m;
}

/* ---------------------------------------------------------------------- */

int FixNosbFamily::unpack_exchange(int nlocal, double *buf)
{
  int m = 0;
  npartner[nlocal] = static_cast<int>(buf[m++]);
  for (int b = 0; b < npartner[nlocal]; b++) {
    partner[nlocal][b] = (tagint) ubuf(buf[m++]).i;
    omega[nlocal][b] = buf[m++];
  }
  for (int k = 0; k < 9; k++) kinv[nlocal][k] = buf[m++];
  kregular[nlocal] = static_cast<int>(buf[m++]);
  vinit[nlocal] = buf[m++];
  lamref[nlocal] = buf[m++];
  owntag[nlocal] = (tagint) ubuf(buf[m++]).i;
  return m;
}

/* ----------------------------------------------------------------------
   global state: whether the families exist, the largest family, the reference box
------------------------------------------------------------------------- */

void FixNosbFamily::write_restart(FILE *fp)
{
  double list[NGLOBAL] = {(double) RESTART_VERSION,
                          (double) built,
                          (double) maxpartner,
                          (double) box.periodic[0],
                          (double) box.periodic[1],
                          (double) box.periodic[2],
                          box.box[0],
                          box.box[1],
                          box.box[2],
                          box.box[3],
                          box.box[4],
                          box.box[5],
                          ubuf(tagmax0).d};
  if (comm->me == 0) {
    int size = NGLOBAL * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), NGLOBAL, fp);
  }
}

/* ----------------------------------------------------------------------
   a file of another format version is refused before its per-atom data are read
------------------------------------------------------------------------- */

void FixNosbFamily::restart(char *buf)
{
  auto list = (double *) buf;
  if (list[0] != (double) RESTART_VERSION)
    error->all(FLERR,
               "Pair peri/nosb: the restart file holds bond families of another format version "
               "({} instead of {}): write the restart file again with this build (or use the "
               "build that wrote it)",
               list[0], (int) RESTART_VERSION);
  built = static_cast<int>(list[1]);
  maxpartner = std::max(static_cast<int>(list[2]), 1);
  for (int k = 0; k < 3; k++) box.periodic[k] = static_cast<int>(list[3 + k]);
  for (int k = 0; k < 6; k++) box.box[k] = list[6 + k];
  tagmax0 = (tagint) ubuf(list[12]).i;
  maxexchange = 1 + NATOMDATA + NBONDDATA * maxpartner;

  // second dimension of the 2d arrays changes: reallocate before per-atom data arrive

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
  const int m = pack_exchange(i, &buf[1]);
  buf[0] = m + 1;
  return m + 1;
}

/* ---------------------------------------------------------------------- */

void FixNosbFamily::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  unpack_exchange(nlocal, &extra[nlocal][m + 1]);
}

/* ---------------------------------------------------------------------- */

int FixNosbFamily::maxsize_restart()
{
  return 2 + NATOMDATA + NBONDDATA * maxpartner;
}

/* ---------------------------------------------------------------------- */

int FixNosbFamily::size_restart(int i)
{
  int n = 0;
  for (int b = 0; b < npartner[i]; b++)
    if (partner[i][b]) n++;
  return 2 + NATOMDATA + NBONDDATA * n;
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
