/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/mesh: the triangles of the meshes read by read_mesh, per atom (what is kept and
   when, deleted atoms, restart and data files: doc/read_mesh.rst). At every init the atom IDs
   must be those the triangles were stored with, and triangles that lost a vertex are dropped.
   Per-atom records (exchange, restart, border, output): core mesh/vertex_records.h. Data
   files: fix_nosb_mesh_data.cpp.
------------------------------------------------------------------------- */

#include "fix_nosb_mesh.h"
#include "restart_records.h"

#include "mesh/lost_vertices.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_requirements.h"
#include "mesh/vertex_records.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"
#include "modify.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

// global restart data: format version, nmesh, ntriangles
static constexpr int NGLOBAL = 3;
static constexpr int RESTART_VERSION = 1;
// columns of the per-atom array: mesh, thickness, ntri, normal0 x y z
static constexpr int NOUTPUT = PeriSISSM::kVertexOutputs;
static constexpr auto kBorder = PeriSISSM::VertexRecord::kBorder;

/* ---------------------------------------------------------------------- */

FixNosbMesh::FixNosbMesh(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), nmesh(0), ntriangles(0), owntag(nullptr), output(nullptr),
    normals_at_setup(0)
{
  std::string other;
  for (const auto &fix : modify->get_fix_by_style("^nosb/mesh$"))
    if (fix != this && other.empty()) other = fix->id;
  const std::string unmet = PeriSISSM::mesh_fix_unmet(
      {arg, arg + narg}, igroup == 0, atom->tag_enable && atom->map_style != Atom::MAP_NONE, other);
  if (!unmet.empty()) error->all(FLERR, unmet);

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  peratom_flag = 1;
  size_peratom_cols = NOUTPUT;
  peratom_freq = 1;
  maxexchange = PeriSISSM::kVertexScalars + 2 * MAXTRI;
  comm_border = PeriSISSM::kVertexBorderScalars + 2 * MAXTRI;
  comm_forward = 3;
  wd_header = 1;
  wd_section = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  atom->add_callback(Atom::BORDER);
  for (int i = 0; i < atom->nmax; i++) set_arrays(i);
}

/* ---------------------------------------------------------------------- */

FixNosbMesh::~FixNosbMesh()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  atom->delete_callback(id, Atom::BORDER);

  memory->destroy(mesh);
  memory->destroy(thickness);
  memory->destroy(ntri);
  memory->destroy(tri);
  memory->destroy(normal0);
  memory->destroy(owntag);
  memory->destroy(output);
}

/* ----------------------------------------------------------------------
   no per-step work: the data change only with the atoms
------------------------------------------------------------------------- */

int FixNosbMesh::setmask()
{
  return 0;
}

/* ---------------------------------------------------------------------- */

FixNosbMesh *FixNosbMesh::find(LAMMPS *lmp)
{
  const auto fixes = lmp->modify->get_fix_by_style("^nosb/mesh$");
  return fixes.empty() ? nullptr : dynamic_cast<FixNosbMesh *>(fixes[0]);
}

MeshView *MeshView::find(LAMMPS *lmp)
{
  return FixNosbMesh::find(lmp);
}

MeshView *MeshView::restore(LAMMPS *lmp)
{
  return FixNosbMesh::restore(lmp);
}

/* ----------------------------------------------------------------------
   after read_restart (until the first run or init clears the restart data), LAMMPS gives a
   new fix the state stored under its ID and style. Modify keeps to itself which fixes the
   file holds, so "NOSB_MESH all nosb/mesh" is defined and kept only if it got data.
------------------------------------------------------------------------- */

FixNosbMesh *FixNosbMesh::restore(LAMMPS *lmp)
{
  FixNosbMesh *fix = find(lmp);
  Modify *modify = lmp->modify;
  if (fix || (modify->nfix_restart_global == 0 && modify->nfix_restart_peratom == 0)) return fix;
  fix = dynamic_cast<FixNosbMesh *>(modify->add_fix(std::string(DEFAULT_ID) + " all nosb/mesh"));
  if (fix && fix->restart_reset) return fix;
  modify->delete_fix(DEFAULT_ID);
  return nullptr;
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::init()
{
  check_ids();
  drop_lost_triangles();
  data.rows.clear();
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::setup(int /*vflag*/)
{
  if (normals_at_setup) normals_where_missing();
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::min_setup(int vflag)
{
  setup(vflag);
}

/* ----------------------------------------------------------------------
   fix_modify ID normals yes|no (or any of LAMMPS's boolean words)
------------------------------------------------------------------------- */

int FixNosbMesh::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "normals") == 0) {
    if (narg < 2) utils::missing_cmd_args(FLERR, "fix_modify nosb/mesh normals", error);
    normals_at_setup = utils::logical(FLERR, arg[1], false, lmp);
    return 2;
  }
  return 0;
}

/* ---------------------------------------------------------------------- */

int FixNosbMesh::add_mesh(bigint ntriangles_added)
{
  ntriangles += ntriangles_added;
  return ++nmesh;
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::set_vertex(int i, int meshid, double t, int n, const tagint (*others)[2])
{
  mesh[i] = meshid;
  thickness[i] = t;
  ntri[i] = n;
  for (int k = 0; k < n; k++) {
    tri[i][k][0] = others[k][0];
    tri[i][k][1] = others[k][1];
  }
  normal0[i][0] = normal0[i][1] = normal0[i][2] = 0.0;
  owntag[i] = atom->tag[i];
  refresh_output(i);
}

/* ----------------------------------------------------------------------
   normals: every owned mesh atom, all ranks agree on errors
------------------------------------------------------------------------- */

void FixNosbMesh::vertex_normals(double **x, double **n)
{
  // the image of jtag closest to x[i] (with the positions x)
  auto position = [&](int i, tagint jtag) -> const double * {
    const int j = local_index(jtag);
    return j < 0 ? nullptr : x[PeriSISSM::closest_image(x[i], x, j, atom->sametag)];
  };
  const auto bad = PeriSISSM::vertex_normals(rows(), atom->nlocal, atom->tag, x, position, n);
  const tagint bad_atom = bad.first ? bad.first : MAXTAGINT;
  const tagint bad_vertex = bad.first ? bad.second : MAXTAGINT;

  tagint bad_all;
  MPI_Allreduce(&bad_atom, &bad_all, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  if (bad_all == MAXTAGINT) return;
  tagint vertex = (bad_atom == bad_all) ? bad_vertex : MAXTAGINT, vertex_all;
  MPI_Allreduce(&vertex, &vertex_all, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  error->all(FLERR,
             "Fix nosb/mesh: vertex {} of a triangle of atom {} is neither an owned nor a ghost "
             "atom on its MPI rank: the ghost cutoff {} is shorter than the mesh's edges there; "
             "increase it with comm_modify cutoff",
             vertex_all, bad_all, comm->get_comm_cutoff());
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::set_reference_normals()
{
  vertex_normals(atom->x, normal0);
  for (int i = 0; i < atom->nlocal; i++) refresh_output(i);
  // the ghosts' copies now (border communication keeps them from the next one on)
  comm->forward_comm(this);
}

/* ----------------------------------------------------------------------
   fix_modify normals yes: mesh atoms without a reference normal get one
------------------------------------------------------------------------- */

void FixNosbMesh::normals_where_missing()
{
  const int nlocal = atom->nlocal;
  const auto a = rows();
  int any = 0, any_all;
  for (int i = 0; i < nlocal && !any; i++) any = PeriSISSM::lacks_normal(a, i) ? 1 : 0;
  MPI_Allreduce(&any, &any_all, 1, MPI_INT, MPI_MAX, world);
  if (!any_all) return;

  double **n;
  memory->create(n, std::max(nlocal, 1), 3, "nosb/mesh:n");
  vertex_normals(atom->x, n);
  PeriSISSM::fill_missing_normals(a, nlocal, n);
  for (int i = 0; i < nlocal; i++) refresh_output(i);
  memory->destroy(n);
  comm->forward_comm(this);
}

/* ----------------------------------------------------------------------
   atom->map() with guards: IDs beyond the map (deleted atoms) and stale entries give -1
------------------------------------------------------------------------- */

int FixNosbMesh::local_index(tagint jtag) const
{
  if (jtag <= 0 || jtag > atom->map_tag_max) return -1;
  const int j = atom->map(jtag);
  if (j < 0 || j >= atom->nlocal + atom->nghost || atom->tag[j] != jtag) return -1;
  return j;
}

/* ----------------------------------------------------------------------
   triangles refer to atom IDs: renumbered IDs would connect the wrong atoms
------------------------------------------------------------------------- */

void FixNosbMesh::check_ids()
{
  int renumbered = 0, renumbered_all;
  for (int i = 0; i < atom->nlocal; i++)
    if (mesh[i] && owntag[i] != atom->tag[i]) renumbered = 1;
  MPI_Allreduce(&renumbered, &renumbered_all, 1, MPI_INT, MPI_MAX, world);
  if (renumbered_all)
    error->all(FLERR,
               "Fix nosb/mesh: atom IDs changed after the mesh was read (triangles are stored "
               "by atom ID): use delete_atoms ... compress no, and do not renumber atoms "
               "(reset_atoms id) in a deck with meshes");
}

/* ----------------------------------------------------------------------
   drop triangles whose other vertices no longer exist as atoms of the same mesh (core
   mesh/lost_vertices.h; the vertices not found here are looked for on all ranks); then count
   the triangles of all meshes
------------------------------------------------------------------------- */

void FixNosbMesh::drop_lost_triangles()
{
  const int nlocal = atom->nlocal;
  auto local = [this](tagint t) {
    return local_index(t);
  };
  auto exists_elsewhere = [&](const std::vector<tagint> &wanted) {
    int nme = (int) wanted.size(), ntotal = 0;
    MPI_Allreduce(&nme, &ntotal, 1, MPI_INT, MPI_SUM, world);
    if (!ntotal) return std::vector<int>();
    std::vector<int> counts(comm->nprocs), displs(comm->nprocs);
    MPI_Allgather(&nme, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
    for (int p = 1; p < comm->nprocs; p++) displs[p] = displs[p - 1] + counts[p - 1];
    std::vector<tagint> all(ntotal);
    MPI_Allgatherv(wanted.data(), nme, MPI_LMP_TAGINT, all.data(), counts.data(), displs.data(),
                   MPI_LMP_TAGINT, world);
    std::vector<int> here = PeriSISSM::owned_vertices(all, nlocal, local, mesh);
    std::vector<int> exists(here.size());
    MPI_Allreduce(here.data(), exists.data(), (int) here.size(), MPI_INT, MPI_MAX, world);
    const int first = displs[comm->me] / 2;
    return std::vector<int>(exists.begin() + first, exists.begin() + first + nme / 2);
  };
  PeriSISSM::drop_lost_triangles(rows(), nlocal, local, exists_elsewhere);
  for (int i = 0; i < nlocal; i++)
    if (mesh[i]) refresh_output(i);

  const bigint before = ntriangles, owned = owned_triangles();
  MPI_Allreduce(&owned, &ntriangles, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me == 0 && ntriangles < before)
    error->warning(FLERR,
                   "Fix nosb/mesh: {} mesh triangles lost a vertex (deleted or lost atoms) and "
                   "were dropped; {} remain",
                   before - ntriangles, ntriangles);
}

/* ----------------------------------------------------------------------
   a triangle is written (and counted) by its vertex with the smallest ID
------------------------------------------------------------------------- */

int FixNosbMesh::owned_triangles() const
{
  return PeriSISSM::count_written_triangles(rows(), atom->nlocal, atom->tag);
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::refresh_output(int i)
{
  PeriSISSM::output_row(rows(), i, output[i]);
}

/* ---------------------------------------------------------------------- */

PeriSISSM::VertexArrays<tagint> FixNosbMesh::rows() const
{
  return {mesh, thickness, owntag, normal0, ntri, tri};
}

/* ---------------------------------------------------------------------- */

double FixNosbMesh::memory_usage()
{
  const double nmax = atom->nmax;
  return nmax *
      (2.0 * sizeof(int) + sizeof(tagint) + (4.0 + NOUTPUT) * sizeof(double) +
       2.0 * MAXTRI * sizeof(tagint));
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::grow_arrays(int nmax)
{
  memory->grow(mesh, nmax, "nosb/mesh:mesh");
  memory->grow(thickness, nmax, "nosb/mesh:thickness");
  memory->grow(ntri, nmax, "nosb/mesh:ntri");
  memory->grow(tri, nmax, MAXTRI, 2, "nosb/mesh:tri");
  memory->grow(normal0, nmax, 3, "nosb/mesh:normal0");
  memory->grow(owntag, nmax, "nosb/mesh:owntag");
  memory->grow(output, nmax, NOUTPUT, "nosb/mesh:output");
  array_atom = output;
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::copy_arrays(int i, int j, int /*delflag*/)
{
  PeriSISSM::copy_vertex(rows(), i, j);
  for (int d = 0; d < NOUTPUT; d++) output[j][d] = output[i][d];
}

/* ----------------------------------------------------------------------
   a new atom is not a mesh vertex, unless read_data has just made it one (its section is read
   before read_data initializes the fixes' data of the new atoms)
------------------------------------------------------------------------- */

void FixNosbMesh::set_arrays(int i)
{
  if (data.rows.erase(i)) return;
  PeriSISSM::clear_vertex(rows(), i);
  refresh_output(i);
}

/* ----------------------------------------------------------------------
   per atom: mesh id; for a mesh vertex then thickness, owntag, normal0, ntri and the
   2 x ntri vertex IDs
------------------------------------------------------------------------- */

int FixNosbMesh::pack_exchange(int i, double *buf)
{
  return PeriSISSM::pack_vertex(rows(), i, buf);
}

/* ---------------------------------------------------------------------- */

int FixNosbMesh::unpack_exchange(int nlocal, double *buf)
{
  const int m = PeriSISSM::unpack_vertex(rows(), nlocal, buf);
  refresh_output(nlocal);
  return m;
}

/* ----------------------------------------------------------------------
   ghosts: mesh id; for a mesh vertex then thickness, ntri and the vertex IDs
------------------------------------------------------------------------- */

int FixNosbMesh::pack_border(int n, int *list, double *buf)
{
  return PeriSISSM::pack_vertices(rows(), n, list, buf, kBorder);
}

/* ---------------------------------------------------------------------- */

int FixNosbMesh::unpack_border(int n, int first, double *buf)
{
  return PeriSISSM::unpack_vertices(rows(), n, first, buf, kBorder);
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::write_restart(FILE *fp)
{
  const double list[NGLOBAL] = {(double) RESTART_VERSION, (double) nmesh, ubuf(ntriangles).d};
  write_global_record(fp, comm->me, list, NGLOBAL);
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::restart(char *buf)
{
  auto list = (double *) buf;
  if (list[0] != (double) RESTART_VERSION)
    error->all(FLERR,
               "Fix nosb/mesh: the restart file holds mesh data of another format version ({} "
               "instead of {}): write the restart file again with this build (or use the build "
               "that wrote it)",
               list[0], RESTART_VERSION);
  nmesh = static_cast<int>(list[1]);
  ntriangles = (bigint) ubuf(list[2]).i;
}

/* ----------------------------------------------------------------------
   per-atom restart data: size first (as other fixes expect), then as in pack_exchange
------------------------------------------------------------------------- */

int FixNosbMesh::pack_restart(int i, double *buf)
{
  return pack_sized_record(buf, [&](double *rec) {
    return pack_exchange(i, rec);
  });
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::unpack_restart(int nlocal, int nth)
{
  unpack_exchange(nlocal, fix_record(atom->extra, nlocal, nth) + 1);
}

/* ---------------------------------------------------------------------- */

int FixNosbMesh::maxsize_restart()
{
  return 1 + PeriSISSM::kVertexScalars + 2 * MAXTRI;
}

/* ---------------------------------------------------------------------- */

int FixNosbMesh::size_restart(int i)
{
  return 1 + PeriSISSM::vertex_record_size(mesh[i], ntri[i]);
}

/* ----------------------------------------------------------------------
   forward communication of the reference normals (set_reference_normals)
------------------------------------------------------------------------- */

int FixNosbMesh::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  int m = 0;
  for (int l = 0; l < n; l++)
    for (int d = 0; d < 3; d++) buf[m++] = normal0[list[l]][d];
  return m;
}

void FixNosbMesh::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int d = 0; d < 3; d++) normal0[i][d] = buf[m++];
}
