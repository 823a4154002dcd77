/* PERI-SISSM core: checks of triangle meshes (see triangle_mesh.h). */
#include "mesh/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace PeriSISSM {

namespace {

  [[noreturn]] void fail(const std::string &filename, int line, const std::string &what)
  {
    throw std::runtime_error("mesh file " + filename +
                             (line > 0 ? " line " + std::to_string(line) : std::string()) + ": " +
                             what);
  }

  // file number (1-based) of a vertex
  std::string vertex_name(int v)
  {
    return std::to_string(v + 1);
  }

  // the triangles of an undirected edge, with the direction they pass it in
  struct EdgeUse {
    int count = 0;
    int triangle[2] = {-1, -1};
    bool forward[2] = {false, false};    // from the smaller vertex index to the larger
  };

  // |(b - a) x (c - a)| against the longest edge squared: 0 for a degenerate triangle
  bool zero_area(const std::array<double, 3> &a, const std::array<double, 3> &b,
                 const std::array<double, 3> &c)
  {
    double e1[3], e2[3], e3[3];
    for (int k = 0; k < 3; k++) {
      e1[k] = b[k] - a[k];
      e2[k] = c[k] - a[k];
      e3[k] = c[k] - b[k];
    }
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    const double twice_area = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double longest = 0.0;
    for (const double *e : {e1, e2, e3})
      longest = std::max(longest, e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    return !(twice_area > 1.0e-12 * longest);
  }

}    // namespace

void check_mesh(const TriangleMesh &mesh, const std::string &filename, int maxtri)
{
  const int nvertex = (int) mesh.vertices.size();
  const int ntriangle = (int) mesh.triangles.size();
  if (ntriangle == 0) fail(filename, 0, "the file has no faces (f lines)");

  // zero-area triangles (a repeated vertex included)

  for (int t = 0; t < ntriangle; t++) {
    const auto &tri = mesh.triangles[t];
    const std::string names =
        vertex_name(tri[0]) + " " + vertex_name(tri[1]) + " " + vertex_name(tri[2]);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      fail(filename, mesh.triangle_line[t],
           "the triangle of vertices " + names + " repeats a vertex (zero area)");
    if (zero_area(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]))
      fail(filename, mesh.triangle_line[t],
           "the triangle of vertices " + names + " has zero area (its vertices are collinear)");
  }

  // edges: each in one or two triangles, passed in opposite directions by two

  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(3 * (size_t) ntriangle);
  auto key = [nvertex](int a, int b) {
    const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
    return lo * (std::uint64_t) nvertex + hi;
  };
  for (int t = 0; t < ntriangle; t++) {
    const auto &tri = mesh.triangles[t];
    for (int c = 0; c < 3; c++) {
      const int a = tri[c], b = tri[(c + 1) % 3];
      EdgeUse &use = edges[key(a, b)];
      if (use.count == 2)
        fail(filename, mesh.triangle_line[t],
             "the edge between vertices " + vertex_name(std::min(a, b)) + " and " +
                 vertex_name(std::max(a, b)) +
                 " is shared by more than two triangles (faces of lines " +
                 std::to_string(mesh.triangle_line[use.triangle[0]]) + ", " +
                 std::to_string(mesh.triangle_line[use.triangle[1]]) + " and " +
                 std::to_string(mesh.triangle_line[t]) + "): the mesh is not a manifold");
      use.triangle[use.count] = t;
      use.forward[use.count] = a < b;
      use.count++;
    }
  }
  for (int t = 0; t < ntriangle; t++) {
    const auto &tri = mesh.triangles[t];
    for (int c = 0; c < 3; c++) {
      const int a = tri[c], b = tri[(c + 1) % 3];
      const EdgeUse &use = edges[key(a, b)];
      if (use.count == 2 && use.triangle[1] == t && use.forward[0] == use.forward[1])
        fail(filename, mesh.triangle_line[t],
             "this face and the face of line " +
                 std::to_string(mesh.triangle_line[use.triangle[0]]) +
                 " both pass their shared edge from vertex " + vertex_name(a) + " to vertex " +
                 vertex_name(b) +
                 ": inconsistent orientation (list the vertices of every face in the same "
                 "sense, e.g. counterclockwise seen from the side the normals point to)");
    }
  }

  // every vertex in at least one and at most maxtri triangles

  std::vector<int> valence(nvertex, 0);
  for (const auto &tri : mesh.triangles)
    for (int c = 0; c < 3; c++) valence[tri[c]]++;
  int unused = 0, first_unused = -1;
  for (int v = 0; v < nvertex; v++) {
    if (valence[v] == 0) {
      if (first_unused < 0) first_unused = v;
      unused++;
    }
  }
  if (unused)
    fail(filename, mesh.vertex_line[first_unused],
         "vertex " + vertex_name(first_unused) + " is used by no face" +
             (unused > 1 ? " (and " + std::to_string(unused - 1) + " more vertices)" : "") +
             ": remove unused vertices from the file");
  for (int v = 0; v < nvertex; v++)
    if (valence[v] > maxtri)
      fail(filename, mesh.vertex_line[v],
           "vertex " + vertex_name(v) + " is in " + std::to_string(valence[v]) +
               " triangles, more than the " + std::to_string(maxtri) +
               " that a mesh vertex may have: refine or remesh around it");
}

std::vector<std::vector<std::array<int, 2>>>
vertex_triangles(int nvertex, const std::vector<std::array<int, 3>> &triangles)
{
  std::vector<std::vector<std::array<int, 2>>> at(nvertex);
  for (int t = 0; t < (int) triangles.size(); t++)
    for (int c = 0; c < 3; c++) at[triangles[t][c]].push_back({t, c});
  return at;
}

std::vector<double> pack_mesh(const TriangleMesh &mesh)
{
  std::vector<double> buf = {(double) mesh.vertices.size(), (double) mesh.triangles.size()};
  for (const auto &v : mesh.vertices) buf.insert(buf.end(), v.begin(), v.end());
  buf.insert(buf.end(), mesh.vertex_line.begin(), mesh.vertex_line.end());
  for (const auto &t : mesh.triangles) buf.insert(buf.end(), t.begin(), t.end());
  buf.insert(buf.end(), mesh.triangle_line.begin(), mesh.triangle_line.end());
  return buf;
}

TriangleMesh unpack_mesh(const std::vector<double> &buf)
{
  TriangleMesh mesh;
  const size_t nv = (size_t) buf[0], nt = (size_t) buf[1];
  size_t m = 2;
  mesh.vertices.resize(nv);
  for (auto &v : mesh.vertices)
    for (auto &c : v) c = buf[m++];
  for (size_t k = 0; k < nv; k++) mesh.vertex_line.push_back((int) buf[m++]);
  mesh.triangles.resize(nt);
  for (auto &t : mesh.triangles)
    for (auto &c : t) c = (int) buf[m++];
  for (size_t k = 0; k < nt; k++) mesh.triangle_line.push_back((int) buf[m++]);
  return mesh;
}

}    // namespace PeriSISSM
