// A mesh file placed in the box for read_mesh: positions and areas of the placed vertices,
// which vertices a sub-domain owns (wrapped, grown, outside a fixed face), the triangles of a
// vertex as atom IDs, the mesh sent as one array, and the file read from disk.
#include "mesh/obj_file.h"
#include "mesh/place_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

using namespace PeriSISSM;

namespace {

// the unit square (0,0)-(1,1) in the xy plane as two counterclockwise triangles
TriangleMesh square()
{
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.vertex_line = {1, 2, 3, 4};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.triangle_line = {5, 6};
  return mesh;
}

// the box [0, 2)^3 (no boundary fixed, not periodic), sub-domain the half x < 1
MeshBox half_box()
{
  MeshBox box = {};
  for (int d = 0; d < 3; d++) {
    box.lo[d] = box.sublo[d] = 0.0;
    box.hi[d] = box.subhi[d] = 2.0;
  }
  box.subhi[0] = 1.0;
  return box;
}

}    // namespace

TEST(PlaceMesh, PlacesEveryVertexAndSumsTheAreas)
{
  Placement placement;
  placement.scale = 2.0;
  placement.theta = 90.0;
  placement.offset[2] = 0.5;
  const PlacedMesh placed = place_mesh(square(), placement);
  ASSERT_EQ(placed.x.size(), 4u);
  for (int k = 0; k < 4; k++) {
    double x[3];
    place(placement, square().vertices[k].data(), x);
    for (int d = 0; d < 3; d++) EXPECT_EQ(placed.x[k][d], x[d]);
  }
  // (1, 0, 0) scaled to (2, 0, 0), turned by 90 degrees about z to (0, 2, 0), lifted by 0.5
  EXPECT_NEAR(placed.x[1][0], 0.0, 1e-15);
  EXPECT_NEAR(placed.x[1][1], 2.0, 1e-15);
  EXPECT_EQ(placed.x[1][2], 0.5);
  // the square of side 2: area 4; the corners of both triangles get 4/3, the others 2/3
  EXPECT_NEAR(placed.total_area, 4.0, 1e-14);
  EXPECT_NEAR(placed.area[0], 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(placed.area[1], 2.0 / 3.0, 1e-14);
  EXPECT_NEAR(placed.area[2], 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(placed.area[3], 2.0 / 3.0, 1e-14);
}

TEST(SubdomainVertices, OwnsTheVerticesInItsHalfOfTheBox)
{
  std::vector<std::array<double, 3>> c = {{0.5, 1, 1}, {1.0, 1, 1}, {0.0, 0, 0}, {1.5, 1.9, 0}};
  const SubdomainVertices own = subdomain_vertices(half_box(), c);
  EXPECT_EQ(own.mine, std::vector<int>({0, 2}));
  EXPECT_FALSE(own.grows);
  EXPECT_EQ(own.outside, -1);
}

TEST(SubdomainVertices, ShrinkWrappedFacesGrowAndTakeTheVertexOntoThem)
{
  std::vector<std::array<double, 3>> c = {{-0.5, 1, 1}, {1.5, 1, 3.0}};
  const SubdomainVertices own = subdomain_vertices(half_box(), c);
  EXPECT_TRUE(own.grows);
  EXPECT_EQ(c[0][0], 0.0);                         // onto the lower x face: in the sub-domain
  EXPECT_EQ(c[1][2], std::nextafter(2.0, 0.0));    // below the upper z face
  EXPECT_EQ(own.mine, std::vector<int>({0}));
}

TEST(SubdomainVertices, PeriodicRoundOffGoesToTheLowerFace)
{
  MeshBox box = half_box();
  box.periodic[1] = true;
  std::vector<std::array<double, 3>> c = {{0.5, 2.0, 1}};
  const SubdomainVertices own = subdomain_vertices(box, c);
  EXPECT_EQ(c[0][1], 0.0);
  EXPECT_FALSE(own.grows);
  EXPECT_EQ(own.mine, std::vector<int>({0}));
}

TEST(SubdomainVertices, StopsAtTheFirstVertexOutsideAFixedFace)
{
  MeshBox box = half_box();
  box.fixed[2][1] = true;
  box.fixed[1][0] = true;
  std::vector<std::array<double, 3>> c = {{0.5, 1, 1}, {0.5, 1, 2.0}, {0.5, -1, 1}};
  const SubdomainVertices own = subdomain_vertices(box, c);
  EXPECT_EQ(own.outside, 1);    // the upper z face is excluded from the box
  EXPECT_EQ(own.dim, 2);
  EXPECT_EQ(own.side, 1);

  std::vector<std::array<double, 3>> below = {{0.5, -1, 3.0}};
  const SubdomainVertices first = subdomain_vertices(box, below);
  EXPECT_EQ(first.outside, 0);    // y comes before z
  EXPECT_EQ(first.dim, 1);
  EXPECT_EQ(first.side, 0);
}

TEST(CornerIds, TheOtherVerticesInTheTrianglesOrientation)
{
  const TriangleMesh mesh = square();
  const auto at = vertex_triangles(4, mesh.triangles);
  long long others[kMaxVertexTriangles][2];
  // vertex 2 is corner 2 of (0, 1, 2) and corner 1 of (0, 2, 3); vertex j has ID 101 + j
  ASSERT_EQ(corner_ids(at[2], mesh.triangles, 101LL, others), 2);
  EXPECT_EQ(others[0][0], 101);
  EXPECT_EQ(others[0][1], 102);
  EXPECT_EQ(others[1][0], 104);
  EXPECT_EQ(others[1][1], 101);
  EXPECT_EQ(corner_ids(at[1], mesh.triangles, 101LL, others), 1);
  EXPECT_EQ(others[0][0], 103);
  EXPECT_EQ(others[0][1], 101);
}

TEST(PackMesh, UnpacksToTheSameMesh)
{
  TriangleMesh mesh = square();
  mesh.vertices[2] = {0.1, -2.5e-7, 1e300};
  const TriangleMesh back = unpack_mesh(pack_mesh(mesh));
  EXPECT_EQ(back.vertices, mesh.vertices);
  EXPECT_EQ(back.vertex_line, mesh.vertex_line);
  EXPECT_EQ(back.triangles, mesh.triangles);
  EXPECT_EQ(back.triangle_line, mesh.triangle_line);
  EXPECT_TRUE(unpack_mesh(pack_mesh(TriangleMesh())).vertices.empty());
}

TEST(ReadObjFile, ReadsTheFileAsParseObjAndNamesAMissingOne)
{
  const std::string text = "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string name = testing::TempDir() + "read_obj_file_test.obj";
  FILE *fp = fopen(name.c_str(), "wb");
  ASSERT_NE(fp, nullptr);
  fputs(text.c_str(), fp);
  fclose(fp);
  const TriangleMesh read = read_obj_file(name);
  const TriangleMesh parsed = parse_obj(text, name);
  remove(name.c_str());
  EXPECT_EQ(read.vertices, parsed.vertices);
  EXPECT_EQ(read.triangles, parsed.triangles);
  EXPECT_EQ(read.triangle_line, std::vector<int>({5}));

  try {
    read_obj_file(name);
    FAIL() << "no error for a missing file";
  } catch (std::runtime_error &e) {
    EXPECT_EQ(std::string(e.what()).find("cannot open mesh file " + name + ": "), 0u) << e.what();
  }
}
