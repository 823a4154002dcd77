/* PERI-SISSM core: the Mesh Triangles section of data files (fix nosb/mesh, read_data): one
   line "ID mesh-id thickness v1 v2 v3" per triangle, its vertices' atom IDs in the triangle's
   orientation. The words are converted as LAMMPS's ValueTokenizer converts them (std::stoi,
   std::stoll, std::stod over the whole word, IDs within the range of the ID type), with its
   error texts. Errors are thrown as std::invalid_argument ("Fix nosb/mesh: ...") naming the line
   and the section.
*/
#ifndef PERISISSM_MESH_DATA_TRIANGLES_H
#define PERISISSM_MESH_DATA_TRIANGLES_H

#include "mesh/vertex_records.h"

#include <string>
#include <unordered_set>
#include <vector>

namespace PeriSISSM {

struct DataTriangle {
  int mesh;            // mesh id, plus the offset of the read
  double thickness;    // > 0
  long long v[3];      // vertex IDs, plus the offset of the read, distinct
  std::string line;    // the line without leading and trailing blanks (for messages)
};

// Inputs: buf (n lines, each ending in '\n'), keyword (the section's name), id_offset and
// mesh_offset (added to the vertex IDs and to the mesh id), max_id (the largest ID of the ID
// type; the words of IDs must lie in [-max_id - 1, max_id]).
// Outputs: the n triangles. Throws std::invalid_argument at the first line (in file order) that
// is missing, has not six words, has a word that is no number of its kind, or gives a mesh id
// below 1, a thickness not above 0 or a repeated vertex.
std::vector<DataTriangle> parse_data_triangles(const char *buf, int n, const std::string &keyword,
                                               long long id_offset, int mesh_offset,
                                               long long max_id);

// read_data's reads of the section: the header line "N mesh triangles" opens one, the section's
// lines (read in chunks) close it when all N are read.
struct DataSectionRead {
  bool open = false;               // a header line was read, its section is not complete
  long long announced = 0;         // triangles announced by the header line
  long long nread = 0;             // section lines read so far
  int mesh_offset = 0;             // added to the mesh ids of the file (those of the deck)
  int first_row = 0;               // atoms from this row on are new atoms of the read
  std::unordered_set<int> rows;    // rows the section set (kept when new atoms are cleared)

  // The header line (its first word N, converted as ValueTokenizer::next_bigint does) opens a
  // read of N triangles after the deck's nmesh meshes and nlocal atoms. Throws
  // std::invalid_argument ("Fix nosb/mesh: ...", naming the line) when N is no integer or < 0.
  void start(const std::string &line, int nmesh, int nlocal);
  // n more section lines were read
  void read(long long n);
};

// What store_data_corner did.
enum class DataCorner { kStored, kOtherMesh, kFull };

// Row i (an owned atom with ID tag) is corner c of triangle v of mesh meshid, thickness t. A row
// of this read's new atoms (i >= first_row, not in rows) starts as no mesh vertex. Unless it is
// a vertex of another mesh (kOtherMesh, nothing stored), the row takes the mesh id, the
// thickness, owntag = tag, a zero normal and the triangle (add_corner; kFull when it has maxtri
// triangles already), and joins rows.
template <class Id>
DataCorner store_data_corner(const VertexArrays<Id> &a, int i, Id tag, const Id v[3], int c,
                             int meshid, double t, int first_row, std::unordered_set<int> &rows,
                             int maxtri)
{
  if (i >= first_row && !rows.count(i)) {
    a.mesh[i] = 0;
    a.ntri[i] = 0;
  }
  if (a.mesh[i] && a.mesh[i] != meshid) return DataCorner::kOtherMesh;
  a.mesh[i] = meshid;
  a.thickness[i] = t;
  a.owntag[i] = tag;
  a.normal0[i][0] = a.normal0[i][1] = a.normal0[i][2] = 0.0;
  if (!add_corner(a, i, v, c, maxtri)) return DataCorner::kFull;
  rows.insert(i);
  return DataCorner::kStored;
}

}    // namespace PeriSISSM

#endif
