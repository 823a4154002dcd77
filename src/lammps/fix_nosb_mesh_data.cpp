/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/mesh, data files: the header line "N mesh triangles" and the section "Mesh
   Triangles" (core mesh/data_triangles.h; doc/read_mesh.rst), written by write_data and read
   by read_data ... fix NOSB_MESH "mesh triangles" "Mesh Triangles".
------------------------------------------------------------------------- */

#include "fix_nosb_mesh.h"

#include "mesh/vertex_records.h"

#include "atom.h"
#include "error.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   write_data: "N mesh triangles" in the header (rank 0 only: ntriangles is kept on all ranks,
   counted at every init, which write_data does first)
------------------------------------------------------------------------- */

void FixNosbMesh::write_data_header(FILE *fp, int /*mth*/)
{
  utils::print(fp, "{} mesh triangles\n", ntriangles);
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::write_data_section_size(int /*mth*/, int &nx, int &ny)
{
  const int n = owned_triangles();
  bigint nbig = n, nall;
  MPI_Allreduce(&nbig, &nall, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (nall != ntriangles)
    error->all(FLERR,
               "Fix nosb/mesh: write_data found {} mesh triangles, but the header says {}: the "
               "triangle lists of the atoms are inconsistent",
               nall, ntriangles);
  nx = n;
  ny = 5;    // mesh id, thickness, three vertex IDs
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::write_data_section_pack(int /*mth*/, double **buf)
{
  PeriSISSM::pack_written_triangles(rows(), atom->nlocal, atom->tag, buf);
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::write_data_section_keyword(int /*mth*/, FILE *fp)
{
  fputs("\nMesh Triangles\n\n", fp);
}

/* ---------------------------------------------------------------------- */

void FixNosbMesh::write_data_section(int /*mth*/, FILE *fp, int n, double **buf, int index)
{
  for (int k = 0; k < n; k++)
    utils::print(fp, "{} {} {} {} {} {}\n", index + k, (int) buf[k][0], buf[k][1],
                 (tagint) ubuf(buf[k][2]).i, (tagint) ubuf(buf[k][3]).i,
                 (tagint) ubuf(buf[k][4]).i);
}

/* ----------------------------------------------------------------------
   read_data ... fix ID "mesh triangles" "Mesh Triangles": the header line "N mesh triangles"
   starts a new read; its mesh ids follow those of the deck
------------------------------------------------------------------------- */

void FixNosbMesh::read_data_header(char *line)
{
  try {
    data.start(line, nmesh, atom->nlocal);
  } catch (std::invalid_argument &e) {
    error->all(FLERR, e.what());
  }
}

/* ---------------------------------------------------------------------- */

bigint FixNosbMesh::read_data_skip_lines(char *keyword)
{
  if (!data.open)
    error->all(FLERR,
               "Fix nosb/mesh: the data file's {} section needs its header line 'N mesh "
               "triangles': read it with read_data ... fix {} \"mesh triangles\" \"{}\"",
               keyword, id, keyword);
  data.read(0);    // closes the read of an empty section
  return data.announced;
}

/* ----------------------------------------------------------------------
   lines "ID mesh thickness v1 v2 v3" (core mesh/data_triangles.h): each owned vertex stores the
   triangle rotated to start at it; every vertex must be an atom (of the data file: IDs get the
   read_data offset)
------------------------------------------------------------------------- */

void FixNosbMesh::read_data_section(char *keyword, int n, char *buf, tagint id_offset)
{
  std::vector<PeriSISSM::DataTriangle> triangles;
  try {
    triangles =
        PeriSISSM::parse_data_triangles(buf, n, keyword, id_offset, data.mesh_offset, MAXTAGINT);
  } catch (std::invalid_argument &e) {
    error->all(FLERR, e.what());
  }
  const auto a = rows();
  std::vector<int> owned(3 * n, 0), owned_all(3 * n);
  int meshmax = nmesh;
  for (int l = 0; l < n; l++) {
    const PeriSISSM::DataTriangle &t = triangles[l];
    const tagint v[3] = {(tagint) t.v[0], (tagint) t.v[1], (tagint) t.v[2]};
    meshmax = std::max(meshmax, t.mesh);
    for (int c = 0; c < 3; c++) {
      const int i = local_index(v[c]);
      if (i < 0 || i >= atom->nlocal) continue;
      owned[3 * l + c] = 1;
      const auto stored = PeriSISSM::store_data_corner(
          a, i, atom->tag[i], v, c, t.mesh, t.thickness, data.first_row, data.rows, MAXTRI);
      if (stored == PeriSISSM::DataCorner::kOtherMesh)
        error->one(FLERR,
                   "Fix nosb/mesh: atom {} is a vertex of mesh {} and of mesh {} (line '{}' of "
                   "the {} section of the data file)",
                   atom->tag[i], mesh[i], t.mesh, t.line, keyword);
      if (stored == PeriSISSM::DataCorner::kFull)
        error->one(FLERR,
                   "Fix nosb/mesh: atom {} is in more than {} triangles of the {} section of the "
                   "data file",
                   atom->tag[i], MAXTRI, keyword);
      refresh_output(i);
    }
  }

  // every vertex is an atom on exactly one rank

  MPI_Allreduce(owned.data(), owned_all.data(), 3 * n, MPI_INT, MPI_SUM, world);
  for (int k = 0; k < 3 * n; k++)
    if (owned_all[k] != 1)
      error->all(FLERR,
                 "Fix nosb/mesh: vertex {} of line '{}' of the {} section of the data file is no "
                 "atom of the deck (vertex IDs are atom IDs of the data file)",
                 triangles[k / 3].v[k % 3], triangles[k / 3].line, keyword);

  nmesh = meshmax;
  ntriangles += n;
  data.read(n);
}
