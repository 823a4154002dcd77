/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/mesh, data files: write_data writes the triangles as a section "Mesh Triangles"
   (one line per triangle: ID, mesh id, thickness, the three vertex IDs in the triangle's
   orientation), announced by the header line "N mesh triangles"; read_data ... fix NOSB_MESH
   "mesh triangles" "Mesh Triangles" reads it back (doc/read_mesh.rst).
------------------------------------------------------------------------- */

#include "fix_nosb_mesh.h"

#include "mesh/vertex_records.h"

#include "atom.h"
#include "error.h"
#include "tokenizer.h"

#include <algorithm>
#include <cstring>
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
  int n = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!mesh[i]) continue;
    for (int k = 0; k < ntri[i]; k++) {
      if (!writes_triangle(i, k)) continue;
      buf[n][0] = mesh[i];
      buf[n][1] = thickness[i];
      buf[n][2] = ubuf(atom->tag[i]).d;
      buf[n][3] = ubuf(tri[i][k][0]).d;
      buf[n][4] = ubuf(tri[i][k][1]).d;
      n++;
    }
  }
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
    ValueTokenizer values(line);
    data_ntriangles = values.next_bigint();
  } catch (TokenizerException &e) {
    error->all(FLERR, "Fix nosb/mesh: invalid mesh triangles line in the data file header: '{}'",
               utils::trim(line));
  }
  if (data_ntriangles < 0)
    error->all(FLERR, "Fix nosb/mesh: negative number of mesh triangles in the data file: '{}'",
               utils::trim(line));
  data_header = 1;
  data_nread = 0;
  data_mesh_offset = nmesh;
  data_first_row = atom->nlocal;
  data_rows.clear();
}

/* ---------------------------------------------------------------------- */

bigint FixNosbMesh::read_data_skip_lines(char *keyword)
{
  if (!data_header)
    error->all(FLERR,
               "Fix nosb/mesh: the data file's {} section needs its header line 'N mesh "
               "triangles': read it with read_data ... fix {} \"mesh triangles\" \"{}\"",
               keyword, id, keyword);
  if (data_nread == data_ntriangles) data_header = 0;    // an empty section
  return data_ntriangles;
}

/* ----------------------------------------------------------------------
   lines "ID mesh thickness v1 v2 v3": each owned vertex stores the triangle rotated to start
   at it; every vertex must be an atom (of the data file: IDs get the read_data offset)
------------------------------------------------------------------------- */

void FixNosbMesh::read_data_section(char *keyword, int n, char *buf, tagint id_offset)
{
  const int nlocal = atom->nlocal;
  tagint *tag = atom->tag;
  const auto a = rows();
  std::vector<int> owned(3 * n, 0), owned_all(3 * n);
  std::vector<tagint> vertices(3 * n);
  std::vector<std::string> lines(n);
  int meshmax = nmesh;

  for (int l = 0; l < n; l++) {
    char *next = strchr(buf, '\n');
    if (!next) error->all(FLERR, "Unexpected end of file while reading data section {}", keyword);
    *next = '\0';
    lines[l] = utils::trim(buf);
    int meshid = 0;
    double t = 0.0;
    tagint v[3];
    try {
      ValueTokenizer values(utils::trim_comment(buf));
      if (values.count() != 6)
        error->all(FLERR,
                   "Fix nosb/mesh: line '{}' of the {} section of the data file has {} values "
                   "instead of 6 (ID mesh thickness v1 v2 v3)",
                   lines[l], keyword, values.count());
      values.next_tagint();
      meshid = values.next_int();
      t = values.next_double();
      for (int c = 0; c < 3; c++) v[c] = values.next_tagint() + id_offset;
    } catch (TokenizerException &e) {
      error->all(FLERR, "Fix nosb/mesh: invalid line '{}' in the {} section of the data file: {}",
                 lines[l], keyword, e.what());
    }
    if (meshid < 1 || !(t > 0.0) || v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      error->all(FLERR,
                 "Fix nosb/mesh: invalid line '{}' in the {} section of the data file: the mesh "
                 "id must be >= 1, the thickness > 0 and the three vertex IDs distinct",
                 lines[l], keyword);
    meshid += data_mesh_offset;
    meshmax = std::max(meshmax, meshid);

    for (int c = 0; c < 3; c++) {
      vertices[3 * l + c] = v[c];
      const int i = local_index(v[c]);
      if (i < 0 || i >= nlocal) continue;
      owned[3 * l + c] = 1;
      if (i >= data_first_row && !data_rows.count(i)) {    // new atom of this read_data
        mesh[i] = 0;
        ntri[i] = 0;
      }
      if (mesh[i] && mesh[i] != meshid)
        error->one(FLERR,
                   "Fix nosb/mesh: atom {} is a vertex of mesh {} and of mesh {} (line '{}' of "
                   "the {} section of the data file)",
                   tag[i], mesh[i], meshid, lines[l], keyword);
      mesh[i] = meshid;
      thickness[i] = t;
      owntag[i] = tag[i];
      normal0[i][0] = normal0[i][1] = normal0[i][2] = 0.0;
      if (!PeriSISSM::add_corner(a, i, v, c, MAXTRI))
        error->one(FLERR,
                   "Fix nosb/mesh: atom {} is in more than {} triangles of the {} section of the "
                   "data file",
                   tag[i], MAXTRI, keyword);
      refresh_output(i);
      data_rows.insert(i);
    }
    buf = next + 1;
  }

  // every vertex is an atom on exactly one rank

  MPI_Allreduce(owned.data(), owned_all.data(), 3 * n, MPI_INT, MPI_SUM, world);
  for (int k = 0; k < 3 * n; k++)
    if (owned_all[k] != 1)
      error->all(FLERR,
                 "Fix nosb/mesh: vertex {} of line '{}' of the {} section of the data file is no "
                 "atom of the deck (vertex IDs are atom IDs of the data file)",
                 vertices[k], lines[k / 3], keyword);

  nmesh = meshmax;
  ntriangles += n;
  data_nread += n;
  if (data_nread == data_ntriangles) data_header = 0;
}
