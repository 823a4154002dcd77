/* PERI-SISSM core: geometry of triangle meshes: placing a mesh file in the box, triangle and
   vertex areas, the closest image of a vertex, and angle-weighted vertex normals.
*/
#ifndef PERISISSM_MESH_MESH_GEOMETRY_H
#define PERISISSM_MESH_MESH_GEOMETRY_H

#include "mesh/vertex_records.h"

#include <array>
#include <utility>
#include <vector>

namespace PeriSISSM {

// Where a mesh file goes: x = R(theta, axis) (scale X) + offset, i.e. scaled about the file's
// origin, then rotated by theta degrees (right-handed) about the axis through the file's
// origin, then shifted.
struct Placement {
  double scale = 1.0;
  double theta = 0.0;                  // degrees
  double axis[3] = {0.0, 0.0, 1.0};    // any nonzero length
  double offset[3] = {0.0, 0.0, 0.0};
};

// Inputs: placement, X (a position in the file). Outputs: x (in the box).
void place(const Placement &placement, const double X[3], double x[3]);

// Where a placed vertex goes along one direction of the box [lo, hi) (read_mesh, after
// LAMMPS's remap): inside it stays; across a periodic boundary a value still outside (by the
// round-off of the wrap) goes to lo; beyond a shrink-wrapped face it goes onto the face (the
// largest double below hi for the upper one) and the box has to grow; beyond a fixed face it is
// outside (left where it is).
enum class BoxFit { kInside, kGrows, kOutside };
// Inputs: c, lo, hi, periodic, fixed (lower and upper face fixed). Outputs: c, side (0 lower,
// 1 upper: the face it was beyond; unchanged when inside or periodic).
BoxFit fit_to_box(double &c, double lo, double hi, bool periodic, const bool fixed[2], int &side);

// area of the triangle (a, b, c)
double triangle_area(const double a[3], const double b[3], const double c[3]);

// Vertex areas: one third of the areas of the triangles at each vertex (they sum to the mesh's
// area).
// Inputs: vertices, triangles (0-based indices into vertices).
// Outputs: one area per vertex.
std::vector<double> vertex_areas(const std::vector<std::array<double, 3>> &vertices,
                                 const std::vector<std::array<int, 3>> &triangles);

// Adds to n the contribution of triangle (i, a, b) to the angle-weighted normal of vertex i:
// its interior angle at i, atan2(|e1 x e2|, e1 . e2), times its unit normal
// e1 x e2 / |e1 x e2|, with e1 = a - i, e2 = b - i. A degenerate triangle adds nothing.
// Inputs: xi, xa, xb (positions of the triangle's vertices in its orientation, i first).
// Outputs: n (accumulated).
void add_angle_weighted_normal(const double xi[3], const double xa[3], const double xb[3],
                               double n[3]);

// n / |n|; a zero vector stays zero. Returns false for a zero vector.
bool normalize_or_zero(double n[3]);

// The image of an atom closest to xi: of row j and the rows of the atom's other images (the
// chain sametag[j], sametag[sametag[j]], ... ending in a negative index, as LAMMPS's
// atom->sametag), the one whose position x[row] has the smallest squared distance to xi (the
// first in the chain of equal ones).
int closest_image(const double xi[3], const double *const *x, int j, const int *sametag);

// Angle-weighted unit normal of a vertex: add_angle_weighted_normal over its triangles
// (i, tri[k][0], tri[k][1]) in the order k = 0..ntri-1, then normalize_or_zero. A triangle with
// a vertex that position() does not find adds nothing.
// Inputs: xi (the vertex's position), ntri, tri (the IDs of the other two vertices of each
// triangle), position (ID -> const double * of that vertex's position, or nullptr).
// Outputs: n. Returns the first ID that position() did not find, 0 if it found all.
template <class Id, class Position>
Id vertex_normal(const double xi[3], int ntri, Id *const *tri, Position position, double n[3])
{
  Id missing = 0;
  n[0] = n[1] = n[2] = 0.0;
  for (int k = 0; k < ntri; k++) {
    const double *xa = position(tri[k][0]);
    const double *xb = position(tri[k][1]);
    if (!xa || !xb) {
      if (!missing) missing = xa ? tri[k][1] : tri[k][0];
      continue;
    }
    add_angle_weighted_normal(xi, xa, xb, n);
  }
  normalize_or_zero(n);
  return missing;
}

// vertex_normal of every mesh row 0..nrows-1 (n zero for the other rows), the other vertices
// of row i's triangles at position(i, id) (nullptr if not found).
// Inputs: a (mesh, ntri, tri), nrows, tag (ID per row), x (position per row), position.
// Outputs: n (nrows rows). Returns (ID of the row, ID of the vertex not found) for the row
// with the smallest ID that misses a vertex, (0, 0) if none does.
template <class Id, class Position>
std::pair<Id, Id> vertex_normals(const VertexArrays<Id> &a, int nrows, const Id *tag,
                                 const double *const *x, Position position, double *const *n)
{
  std::pair<Id, Id> bad(0, 0);
  for (int i = 0; i < nrows; i++) {
    n[i][0] = n[i][1] = n[i][2] = 0.0;
    if (!a.mesh[i]) continue;
    auto at = [&](Id id) {
      return position(i, id);
    };
    const Id missing = vertex_normal(x[i], a.ntri[i], a.tri[i], at, n[i]);
    if (missing && (!bad.first || tag[i] < bad.first)) bad = {tag[i], missing};
  }
  return bad;
}

}    // namespace PeriSISSM

#endif
