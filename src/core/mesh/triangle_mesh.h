/* PERI-SISSM core: triangle meshes (membranes read by read_mesh).

   A TriangleMesh holds the vertices and the triangles of one mesh file, with the file's line of
   every vertex and triangle for error messages. check_mesh() accepts only what a membrane can
   be made of: a manifold surface (each edge in one or two triangles) with a consistent
   orientation, no zero-area triangle, no vertex outside the triangles, and at most
   kMaxVertexTriangles triangles at a vertex. Errors are thrown as std::runtime_error naming the
   file, the line and the vertices.
*/
#ifndef PERISISSM_MESH_TRIANGLE_MESH_H
#define PERISISSM_MESH_TRIANGLE_MESH_H

#include <array>
#include <string>
#include <vector>

namespace PeriSISSM {

// largest number of triangles that may share a vertex (the per-atom storage of the triangles)
constexpr int kMaxVertexTriangles = 16;

struct TriangleMesh {
  std::vector<std::array<double, 3>> vertices;    // positions, in file order
  std::vector<std::array<int, 3>> triangles;      // 0-based vertex indices, file orientation
  std::vector<int> vertex_line;                   // line of each vertex in the file
  std::vector<int> triangle_line;                 // line of the face each triangle comes from
};

// Throws std::runtime_error ("mesh file NAME line L: ...") at the first problem of the mesh:
// a triangle of zero area (relative to its longest edge squared, below 1e-12), an edge shared
// by more than two triangles (non-manifold), two triangles that pass a shared edge in the same
// direction (inconsistent orientation), a vertex used by no triangle, more than maxtri triangles
// at a vertex, or no triangles at all.
// Inputs: mesh, filename (names it in messages), maxtri (at most kMaxVertexTriangles).
void check_mesh(const TriangleMesh &mesh, const std::string &filename,
                int maxtri = kMaxVertexTriangles);

// The triangles at each vertex, as (triangle index, position of the vertex in it: 0, 1, 2),
// in triangle order.
// Inputs: nvertex, triangles (0-based, indices below nvertex).
// Outputs: one list per vertex.
std::vector<std::vector<std::array<int, 2>>>
vertex_triangles(int nvertex, const std::vector<std::array<int, 3>> &triangles);

// The triangles at a vertex as the IDs of their other two vertices in the triangle's
// orientation, vertex j of the mesh having the ID first + j.
// Inputs: at (the vertex's list of vertex_triangles), triangles, first.
// Outputs: others (one row per triangle of at). Returns the number of triangles.
template <class Id>
int corner_ids(const std::vector<std::array<int, 2>> &at,
               const std::vector<std::array<int, 3>> &triangles, Id first, Id (*others)[2])
{
  int n = 0;
  for (const auto &corner : at) {
    const auto &t = triangles[corner[0]];
    others[n][0] = first + t[(corner[1] + 1) % 3];
    others[n][1] = first + t[(corner[1] + 2) % 3];
    n++;
  }
  return n;
}

// The mesh as one array of doubles (to send it whole): the numbers of vertices and triangles,
// then the vertices, their lines, the triangles and their lines (integers are exact as doubles).
std::vector<double> pack_mesh(const TriangleMesh &mesh);
// Inputs: buf from pack_mesh. Outputs: the mesh.
TriangleMesh unpack_mesh(const std::vector<double> &buf);

}    // namespace PeriSISSM

#endif
