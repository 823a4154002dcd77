/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   dump nosb/mesh (doc/dump_nosb_mesh.rst): dump custom selects the vertices (group, and
   dump_modify region and thresh) and packs their rows (ID, unwrapped position, the user's
   fields); each rank adds the triangles its chosen vertices write (the vertex of smallest ID,
   core mesh/vertex_records.h writes_triangle); rank 0 gathers both, assembles the frame, joins
   its pieces across periodic boundaries (core mesh/mesh_frame.h) and writes it (core
   mesh/mesh_files.h) to a file of its own per frame.
------------------------------------------------------------------------- */

#include "dump_nosb_mesh.h"

#include "mesh_view.h"

#include "mesh/vertex_records.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "update.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

using namespace LAMMPS_NS;

namespace {

// the words after the fields: keyword value pairs
const char *const KEYWORDS[] = {"pvd"};

bool is_keyword(const char *word)
{
  for (const char *k : KEYWORDS)
    if (strcmp(word, k) == 0) return true;
  return false;
}

}    // namespace

/* ---------------------------------------------------------------------- */

DumpNosbMeshArgs::DumpNosbMeshArgs(int narg, char **arg)
{
  int iarg = 0;
  for (; iarg < narg && iarg < 5; iarg++) words.emplace_back(arg[iarg]);
  for (const char *head : {"id", "xu", "yu", "zu"}) words.emplace_back(head);
  for (; iarg < narg && !is_keyword(arg[iarg]); iarg++) words.emplace_back(arg[iarg]);
  for (; iarg < narg; iarg++) keywords.emplace_back(arg[iarg]);
  for (std::string &w : words) argv.push_back(&w[0]);
}

/* ---------------------------------------------------------------------- */

DumpNosbMesh::DumpNosbMesh(LAMMPS *lmp, int narg, char **arg) :
    DumpNosbMeshArgs(narg, arg), DumpCustom(lmp, (int) argv.size(), argv.data()), mesh(nullptr)
{
  try {
    format = PeriSISSM::mesh_file_format(filename);
  } catch (std::invalid_argument &e) {
    error->all(FLERR, "Illegal dump nosb/mesh command: {}", e.what());
  }
  if (strchr(filename, '%'))
    error->all(FLERR,
               "Illegal dump nosb/mesh command: file name {} has a %: rank 0 writes "
               "each frame",
               filename);
  const bool vtk = format != PeriSISSM::MeshFileFormat::kObj;

  // the user's fields (after the row head), numbers only
  for (int k = PeriSISSM::kFrameRowHead; k < nfield; k++) {
    if (vtype[k] == Dump::STRING || vtype[k] == Dump::STRING2)
      error->all(FLERR, "Illegal dump nosb/mesh command: field {} is text; fields are numbers",
                 earg[k]);
    if (!vtk)
      error->all(FLERR,
                 "Illegal dump nosb/mesh command: field {}: OBJ files hold no fields "
                 "(write a .vtp or .vtu file for them)",
                 earg[k]);
    fields.push_back({earg[k], vtype[k] == Dump::INT || vtype[k] == Dump::BIGINT});
  }

  if (vtk) series = PeriSISSM::default_series_name(filename);
  for (size_t k = 0; k < keywords.size(); k += 2) {
    const std::string &key = keywords[k];
    if (k + 1 >= keywords.size())
      error->all(FLERR, "Illegal dump nosb/mesh command: keyword {} needs a value", key);
    const std::string &value = keywords[k + 1];
    if (key == "pvd") {
      if (!vtk)
        error->all(FLERR,
                   "Illegal dump nosb/mesh command: pvd {}: a series lists VTK files, "
                   "not OBJ",
                   value);
      if (value == "no")
        series.clear();
      else if (value != "yes") {
        if (!utils::strmatch(value, "\\.pvd$"))
          error->all(FLERR,
                     "Illegal dump nosb/mesh command: pvd {}: yes, no, or a file "
                     "name ending in .pvd",
                     value);
        series = value;
      }
    } else {
      error->all(FLERR, "Illegal dump nosb/mesh command: unknown keyword {}", key);
    }
  }

  // one file per frame ('*' gives each its own name; without it each frame rewrites the file)
  multifile = 1;
  buffer_allow = buffer_flag = 0;
}

/* ---------------------------------------------------------------------- */

void DumpNosbMesh::init_style()
{
  DumpCustom::init_style();
  mesh = MeshView::restore(lmp);
  if (!mesh)
    error->all(FLERR,
               "Dump nosb/mesh {}: the deck has no mesh (read_mesh, or fix nosb/mesh "
               "for a data file's triangles)",
               id);
  const char *refused = sort_flag ? "sort"
      : balance_flag              ? "balance"
      : append_flag               ? "append"
      : maxfiles > 0              ? "maxfiles"
                                  : nullptr;
  if (refused)
    error->all(FLERR,
               "Dump nosb/mesh {}: dump_modify {} does not apply (each frame is a file "
               "of its own, ordered by atom ID)",
               id, refused);
}

/* ----------------------------------------------------------------------
   rank 0 opens the frame's file; a failure is an error on all ranks
------------------------------------------------------------------------- */

void DumpNosbMesh::openfile()
{
  current = utils::star_subst(filename, update->ntimestep, padflag);
  std::string why;
  int ok = 1;
  if (filewriter) {
    fp = fopen(current.c_str(), "w");
    if (!fp) {
      ok = 0;
      why = utils::getsyserror();
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, world);
  if (!ok) error->all(FLERR, "Dump nosb/mesh {}: cannot open file {}: {}", id, current, why);
}

/* ----------------------------------------------------------------------
   dump custom's choice, then only the mesh vertices
------------------------------------------------------------------------- */

int DumpNosbMesh::count()
{
  DumpCustom::count();
  int n = 0;
  for (int k = 0; k < nchoose; k++) {
    const int i = clist[k];
    if (mesh->mesh_of(i))
      clist[n++] = i;
    else
      choose[i] = 0;
  }
  nchoose = n;
  return nchoose;
}

/* ----------------------------------------------------------------------
   dump custom's rows, the triangles of the chosen vertices; both gathered on rank 0, which
   assembles the frame. nme := 0: the base class has nothing more to send.
------------------------------------------------------------------------- */

void DumpNosbMesh::pack(tagint *ids)
{
  DumpCustom::pack(ids);

  std::vector<tagint> tris;    // mesh id and three vertex IDs per triangle
  const tagint *tag = atom->tag;
  for (int k = 0; k < nchoose; k++) {
    const int i = clist[k];
    for (int t = 0; t < mesh->ntri_of(i); t++) {
      const tagint a = mesh->corner_of(i, t, 0), b = mesh->corner_of(i, t, 1);
      if (!PeriSISSM::writes_triangle(tag[i], a, b)) continue;
      tris.insert(tris.end(), {(tagint) mesh->mesh_of(i), tag[i], a, b});
    }
  }

  // gather rows and triangles (counts as ints, as Dump's own buffers)
  const int sizes[2] = {nme * size_one, (int) tris.size()};
  std::vector<int> all(2 * comm->nprocs), rowdisp(comm->nprocs), tridisp(comm->nprocs);
  MPI_Gather(sizes, 2, MPI_INT, all.data(), 2, MPI_INT, 0, world);
  std::vector<int> rowcount(comm->nprocs), tricount(comm->nprocs);
  int nrow = 0, ntri = 0;
  for (int p = 0; p < comm->nprocs; p++) {
    rowcount[p] = all[2 * p];
    tricount[p] = all[2 * p + 1];
    rowdisp[p] = nrow;
    tridisp[p] = ntri;
    nrow += rowcount[p];
    ntri += tricount[p];
  }
  std::vector<double> rows(comm->me == 0 ? nrow : 0);
  std::vector<tagint> alltris(comm->me == 0 ? ntri : 0);
  MPI_Gatherv(buf, sizes[0], MPI_DOUBLE, rows.data(), rowcount.data(), rowdisp.data(), MPI_DOUBLE,
              0, world);
  MPI_Gatherv(tris.data(), sizes[1], MPI_LMP_TAGINT, alltris.data(), tricount.data(),
              tridisp.data(), MPI_LMP_TAGINT, 0, world);
  nme = 0;

  bigint nwritten = 0;
  if (comm->me == 0) {
    std::vector<PeriSISSM::FrameTriangle> triangles;
    for (size_t k = 0; k + 3 < alltris.size(); k += 4)
      triangles.push_back({(int) alltris[k], {alltris[k + 1], alltris[k + 2], alltris[k + 3]}});
    try {
      frame = PeriSISSM::assemble_frame(rows, size_one, triangles);
    } catch (std::invalid_argument &e) {
      error->one(FLERR, "Dump nosb/mesh {}: {}", id, e.what());
    }
    const PeriSISSM::BoxPeriods box = {
        {domain->xprd, 0.0, 0.0},
        {domain->xy, domain->yprd, 0.0},
        {domain->xz, domain->yz, domain->zprd},
        {domain->xperiodic != 0, domain->yperiodic != 0, domain->zperiodic != 0}};
    PeriSISSM::join_pieces(frame, box);
    nwritten = (bigint) frame.triangles.size();
  }
  MPI_Bcast(&nwritten, 1, MPI_LMP_BIGINT, 0, world);
  if (nwritten == 0 && nthresh == 0 && !idregion)
    error->all(FLERR,
               "Dump nosb/mesh {}: group {} holds no mesh triangle (a triangle of "
               "read_mesh is written when its three vertices are in the group)",
               id, group->names[igroup]);
}

/* ----------------------------------------------------------------------
   rank 0: the frame's file, then the series file (written to FILE.tmp and renamed, so that a
   run stopped at any point leaves a complete series)
------------------------------------------------------------------------- */

void DumpNosbMesh::write_footer()
{
  const double time = compute_time();
  std::string text;
  if (format == PeriSISSM::MeshFileFormat::kObj)
    text = PeriSISSM::obj_text(
        frame, fmt::format("dump {} nosb/mesh: step {}, time {}", id, update->ntimestep, time));
  else
    text = PeriSISSM::vtk_text(frame, fields, time, format);
  fwrite(text.data(), 1, text.size(), fp);
  fflush(fp);
  frame = PeriSISSM::MeshFrame();
  if (series.empty()) return;

  PeriSISSM::add_to_series(frames, time, PeriSISSM::name_in_series(current, series));
  const std::string tmp = series + ".tmp", pvd = PeriSISSM::pvd_text(frames);
  FILE *out = fopen(tmp.c_str(), "w");
  bool ok = out != nullptr;
  if (out) {
    ok = fwrite(pvd.data(), 1, pvd.size(), out) == pvd.size();
    ok = fclose(out) == 0 && ok;
  }
  ok = ok && rename(tmp.c_str(), series.c_str()) == 0;
  if (!ok)
    error->one(FLERR, "Dump nosb/mesh {}: cannot write series file {}: {}", id, series,
               utils::getsyserror());
}
