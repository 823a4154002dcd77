// Checks of triangle meshes for read_mesh: a regular grid passes; zero-area triangles,
// non-manifold edges, inconsistent orientation, unused vertices and too many triangles at a
// vertex are refused with the file, line and vertices named.
#include "mesh/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

using namespace PeriSISSM;

namespace {

template <class F> std::string error_of(F f)
{
  try {
    f();
  } catch (std::runtime_error &e) {
    return e.what();
  }
  return "";
}

// nx x ny vertices on the unit-spaced grid of the xy plane, two counterclockwise triangles per
// cell; vertex v on line v + 1, triangle t on line nx*ny + 1 + t
TriangleMesh grid(int nx, int ny)
{
  TriangleMesh mesh;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      mesh.vertices.push_back({(double) i, (double) j, 0.0});
      mesh.vertex_line.push_back((int) mesh.vertices.size());
    }
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      const int a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  for (size_t t = 0; t < mesh.triangles.size(); t++)
    mesh.triangle_line.push_back(nx * ny + 1 + (int) t);
  return mesh;
}

void add_triangle(TriangleMesh &mesh, int a, int b, int c, int line)
{
  mesh.triangles.push_back({a, b, c});
  mesh.triangle_line.push_back(line);
}

void expect_error(const TriangleMesh &mesh, const std::vector<std::string> &parts,
                  int maxtri = kMaxVertexTriangles)
{
  const std::string message = error_of([&] {
    check_mesh(mesh, "m.obj", maxtri);
  });
  ASSERT_FALSE(message.empty());
  for (const auto &part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << message << " lacks " << part;
}

}    // namespace

TEST(TriangleMesh, RegularGridPasses)
{
  EXPECT_NO_THROW(check_mesh(grid(5, 4), "grid.obj"));
}

TEST(TriangleMesh, ClosedSurfacePasses)
{
  // a tetrahedron, outward normals
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.vertex_line = {1, 2, 3, 4};
  add_triangle(mesh, 0, 2, 1, 5);
  add_triangle(mesh, 0, 1, 3, 6);
  add_triangle(mesh, 0, 3, 2, 7);
  add_triangle(mesh, 1, 2, 3, 8);
  EXPECT_NO_THROW(check_mesh(mesh, "tet.obj"));
}

TEST(TriangleMesh, ZeroAreaTrianglesAreRefused)
{
  auto mesh = grid(3, 2);
  mesh.vertices.push_back({5, 0, 0});
  mesh.vertex_line.push_back(99);
  add_triangle(mesh, 1, 2, 6, 40);    // (1,0) (2,0) (5,0): collinear, on the boundary edge
  expect_error(mesh, {"m.obj line 40", "vertices 2 3 7", "zero area", "collinear"});

  auto repeated = grid(3, 2);
  add_triangle(repeated, 1, 4, 1, 41);
  expect_error(repeated, {"m.obj line 41", "vertices 2 5 2", "repeats a vertex"});
}

TEST(TriangleMesh, TinyButRegularTrianglesPass)
{
  auto mesh = grid(3, 3);
  for (auto &v : mesh.vertices)
    for (double &x : v) x *= 1e-9;
  EXPECT_NO_THROW(check_mesh(mesh, "tiny.obj"));
}

TEST(TriangleMesh, EdgeOfThreeTrianglesIsNotAManifold)
{
  auto mesh = grid(2, 2);    // triangles (0 1 3), (0 3 2): edge 0-3 shared
  mesh.vertices.push_back({0.5, 0.5, 1.0});
  mesh.vertex_line.push_back(8);
  add_triangle(mesh, 3, 0, 4, 9);    // a fin on the diagonal
  expect_error(mesh,
               {"m.obj line 9", "vertices 1 and 4", "more than two triangles", "lines 5, 6 and 9",
                "not a manifold"});
}

TEST(TriangleMesh, InconsistentOrientationIsRefused)
{
  auto mesh = grid(3, 2);
  std::swap(mesh.triangles[1][1], mesh.triangles[1][2]);    // (0 4 3) -> (0 3 4)
  // the error names the later of the two faces, the earlier one's line and the edge
  expect_error(mesh,
               {"m.obj line 8: this face and the face of line 7", "from vertex 5 to vertex 1",
                "inconsistent orientation"});
}

TEST(TriangleMesh, UnusedVertexIsNamed)
{
  auto mesh = grid(3, 2);
  mesh.vertices.insert(mesh.vertices.begin() + 2, {9, 9, 9});
  mesh.vertex_line = {1, 2, 3, 4, 5, 6, 7};
  for (auto &t : mesh.triangles)
    for (int &v : t)
      if (v >= 2) v++;
  mesh.vertices.push_back({8, 8, 8});
  mesh.vertex_line.push_back(8);
  expect_error(mesh, {"m.obj line 3", "vertex 3 is used by no face", "and 1 more"});
}

TEST(TriangleMesh, TooManyTrianglesAtAVertex)
{
  // a disk of n triangles around vertex 1
  const int n = kMaxVertexTriangles + 1;
  TriangleMesh mesh;
  mesh.vertices.push_back({0, 0, 0});
  mesh.vertex_line.push_back(1);
  for (int k = 0; k < n; k++) {
    const double a = 2.0 * 3.141592653589793 * k / n;
    mesh.vertices.push_back({std::cos(a), std::sin(a), 0.0});
    mesh.vertex_line.push_back(2 + k);
  }
  for (int k = 0; k < n; k++) add_triangle(mesh, 0, 1 + k, 1 + (k + 1) % n, 100 + k);
  expect_error(mesh, {"m.obj line 1", "vertex 1 is in 17 triangles", "more than the 16"});
  EXPECT_NO_THROW(check_mesh(mesh, "m.obj", n));
}

TEST(TriangleMesh, NoFaces)
{
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}};
  mesh.vertex_line = {1};
  expect_error(mesh, {"m.obj", "no faces"});
}

TEST(TriangleMesh, VertexTrianglesListEveryCorner)
{
  const auto mesh = grid(3, 2);
  const auto at = vertex_triangles(6, mesh.triangles);
  // triangles (0 1 4) (0 4 3) (1 2 5) (1 5 4); vertex 4 = (1,1) is corner 2, 1 and 2 of three
  ASSERT_EQ(at[4].size(), 3u);
  EXPECT_EQ(at[4][0], (std::array<int, 2>{0, 2}));
  EXPECT_EQ(at[4][1], (std::array<int, 2>{1, 1}));
  EXPECT_EQ(at[4][2], (std::array<int, 2>{3, 2}));
  EXPECT_EQ(at[0].size(), 2u);
  EXPECT_EQ(at[2].size(), 1u);
  size_t corners = 0;
  for (const auto &list : at) corners += list.size();
  EXPECT_EQ(corners, 3 * mesh.triangles.size());
}
