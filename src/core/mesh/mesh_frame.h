/* PERI-SISSM core: one frame of a mesh dump (dump nosb/mesh), assembled on the rank that writes
   it from what all ranks sent: one row per vertex (its atom ID, position and fields) and the
   triangles, each sent once by the rank that owns its vertex of smallest ID (writes_triangle in
   mesh/vertex_records.h).

   A frame keeps the triangles whose three vertices sent a row, and the vertices those triangles
   use; the vertices are numbered 0, 1, ... in the order of their atom IDs and the triangles are
   ordered by mesh id, then by their vertex IDs, so that frames of runs on any number of ranks
   are identical files.
*/
#ifndef PERISISSM_MESH_MESH_FRAME_H
#define PERISISSM_MESH_MESH_FRAME_H

#include <array>
#include <vector>

namespace PeriSISSM {

// A triangle as its writing vertex sends it: mesh id and the three vertex IDs in the triangle's
// orientation.
struct FrameTriangle {
  int mesh;
  long long v[3];
};

struct MeshFrame {
  int nfields = 0;                              // values per vertex besides ID and position
  std::vector<long long> ids;                   // atom ID of each vertex, ascending
  std::vector<double> x;                        // 3 per vertex
  std::vector<double> fields;                   // nfields per vertex
  std::vector<std::array<int, 3>> triangles;    // vertex numbers (0-based), in orientation
  std::vector<int> mesh;                        // mesh id of each triangle
};

// values in a vertex row before its fields: atom ID, x, y, z
constexpr int kFrameRowHead = 4;

// Inputs: rows (row-major, ncolumns values per vertex: atom ID, x, y, z, then ncolumns - 4
// fields; any order), ncolumns (>= 4), triangles (any order).
// Outputs: the frame: the triangles whose three vertex IDs have a row, ordered by mesh id, then
// by their vertex IDs; the vertices of these triangles, ordered by ID. Throws
// std::invalid_argument when ncolumns < 4, rows is no multiple of ncolumns, or two rows have
// the same ID.
MeshFrame assemble_frame(const std::vector<double> &rows, int ncolumns,
                         const std::vector<FrameTriangle> &triangles);

// The periods of a box: its edge vectors a = (lx, 0, 0), b = (xy, ly, 0), c = (xz, yz, lz) and
// whether it is periodic along each of them.
struct BoxPeriods {
  double a[3], b[3], c[3];
  bool periodic[3];
};

// Every piece of the frame (vertices connected by triangles) in one piece: its vertex of
// smallest ID stays where it is; each other vertex, reached through the triangles' edges in the
// order of the vertex numbers, moves by whole periods to the image closest to the vertex it is
// reached from (the difference in box fractions rounded to the nearest integers along the
// periodic directions). A vertex whose closest image is where it is does not move (its
// position is not recomputed). A piece that closes on itself across a periodic direction (a
// tube around the box) keeps one seam of triangles across the box.
// Inputs: frame, box. Outputs: frame.x.
void join_pieces(MeshFrame &frame, const BoxPeriods &box);

}    // namespace PeriSISSM

#endif
