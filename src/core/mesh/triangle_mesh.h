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

}    // namespace PeriSISSM

#endif
