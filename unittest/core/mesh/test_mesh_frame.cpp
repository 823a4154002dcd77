// One frame of a mesh dump: the triangles whose vertices all sent a row, their vertices in ID
// order and numbered compactly, the same frame whatever the order of rows and triangles (as
// ranks send them), the errors for malformed input; pieces joined across periodic boundaries
// in orthogonal and triclinic boxes.
#include "mesh/mesh_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

using namespace PeriSISSM;

namespace {

// a vertex row: ID, position (ID + 0.5, -ID, 2 ID), one field (10 ID)
void add_row(std::vector<double> &rows, long long id)
{
  const double d = (double) id;
  rows.insert(rows.end(), {d, d + 0.5, -d, 2.0 * d, 10.0 * d});
}

// two meshes: mesh 1 the square 1-2-3-4 (triangles 1 2 3 and 1 3 4), mesh 2 the triangle 7 8 9
std::vector<FrameTriangle> two_meshes()
{
  return {{2, {7, 8, 9}}, {1, {1, 3, 4}}, {1, {1, 2, 3}}};
}

}    // namespace

TEST(MeshFrame, KeepsTrianglesWithAllVerticesAndNumbersThemByID)
{
  std::vector<double> rows;
  for (long long id : {9, 4, 1, 8, 3, 2, 7}) add_row(rows, id);
  add_row(rows, 5);    // in no triangle: not written
  const MeshFrame f = assemble_frame(rows, 5, two_meshes());
  EXPECT_EQ(f.nfields, 1);
  EXPECT_EQ(f.ids, (std::vector<long long>{1, 2, 3, 4, 7, 8, 9}));
  ASSERT_EQ(f.x.size(), 21u);
  EXPECT_EQ(f.x[3 * 4 + 0], 7.5);    // vertex 4 is atom 7
  EXPECT_EQ(f.x[3 * 4 + 1], -7.0);
  EXPECT_EQ(f.x[3 * 4 + 2], 14.0);
  EXPECT_EQ(f.fields, (std::vector<double>{10, 20, 30, 40, 70, 80, 90}));
  // by mesh id, then vertex IDs; orientation kept
  ASSERT_EQ(f.triangles.size(), 3u);
  EXPECT_EQ(f.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(f.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(f.triangles[2], (std::array<int, 3>{4, 5, 6}));
  EXPECT_EQ(f.mesh, (std::vector<int>{1, 1, 2}));
}

TEST(MeshFrame, DropsTrianglesWithAVertexWithoutRowAndItsLoneVertices)
{
  std::vector<double> rows;
  for (long long id : {1, 2, 3, 7, 8}) add_row(rows, id);    // 4 and 9 are not in the group
  const MeshFrame f = assemble_frame(rows, 5, two_meshes());
  EXPECT_EQ(f.ids, (std::vector<long long>{1, 2, 3}));    // 7 and 8 are in no kept triangle
  ASSERT_EQ(f.triangles.size(), 1u);
  EXPECT_EQ(f.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(f.fields, (std::vector<double>{10, 20, 30}));
}

TEST(MeshFrame, TheSameFrameWhateverTheOrderOfRowsAndTriangles)
{
  // a strip of 40 triangles over the vertices 1..42, IDs spread (3 k), sent in shuffled order
  std::vector<double> rows;
  std::vector<FrameTriangle> tris;
  for (long long k = 1; k <= 42; k++) add_row(rows, 3 * k);
  for (long long k = 1; k <= 40; k++)
    tris.push_back({1 + (int) (k % 3), {3 * k, 3 * k + 3, 3 * k + 6}});
  const MeshFrame ref = assemble_frame(rows, 5, tris);
  EXPECT_EQ(ref.ids.size(), 42u);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; trial++) {
    std::vector<int> order(42);
    for (int k = 0; k < 42; k++) order[k] = k;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<double> shuffled;
    for (int k : order)
      shuffled.insert(shuffled.end(), rows.begin() + 5 * k, rows.begin() + 5 * k + 5);
    std::vector<FrameTriangle> t2 = tris;
    std::shuffle(t2.begin(), t2.end(), rng);
    const MeshFrame f = assemble_frame(shuffled, 5, t2);
    EXPECT_EQ(f.ids, ref.ids);
    EXPECT_EQ(f.x, ref.x);
    EXPECT_EQ(f.fields, ref.fields);
    EXPECT_EQ(f.triangles, ref.triangles);
    EXPECT_EQ(f.mesh, ref.mesh);
  }
  // mesh ids first: all triangles of mesh 1 precede those of mesh 2
  EXPECT_TRUE(std::is_sorted(ref.mesh.begin(), ref.mesh.end()));
}

TEST(MeshFrame, AnEmptyFrameAndRowsWithoutFields)
{
  const MeshFrame empty = assemble_frame({}, 4, two_meshes());
  EXPECT_TRUE(empty.ids.empty());
  EXPECT_TRUE(empty.triangles.empty());
  const MeshFrame bare = assemble_frame({1, 0, 0, 0, 2, 1, 0, 0, 3, 0, 1, 0}, 4, two_meshes());
  EXPECT_EQ(bare.nfields, 0);
  EXPECT_EQ(bare.ids, (std::vector<long long>{1, 2, 3}));
  EXPECT_TRUE(bare.fields.empty());
  EXPECT_EQ(bare.x, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
}

TEST(MeshFrame, RejectsMalformedRows)
{
  EXPECT_THROW(assemble_frame({1, 0, 0}, 3, {}), std::invalid_argument);
  EXPECT_THROW(assemble_frame({1, 0, 0, 0, 2}, 4, {}), std::invalid_argument);
  try {
    assemble_frame({5, 0, 0, 0, 5, 1, 1, 1}, 4, {});
    FAIL() << "no error for a repeated ID";
  } catch (std::invalid_argument &e) {
    EXPECT_EQ(std::string(e.what()), "mesh frame: two vertex rows of atom 5");
  }
}

namespace {

// a frame of the strip of triangles (0 1 2), (1 3 2), (2 3 4), ... over nv vertices at x
MeshFrame strip(const std::vector<std::array<double, 3>> &x)
{
  MeshFrame f;
  for (size_t i = 0; i < x.size(); i++) {
    f.ids.push_back((long long) i + 1);
    f.x.insert(f.x.end(), x[i].begin(), x[i].end());
  }
  for (int i = 0; i + 2 < (int) x.size(); i++) {
    f.triangles.push_back(i % 2 ? std::array<int, 3>{i, i + 2, i + 1}
                                : std::array<int, 3>{i, i + 1, i + 2});
    f.mesh.push_back(1);
  }
  return f;
}

BoxPeriods orthogonal(double lx, double ly, double lz, bool px, bool py, bool pz)
{
  return {{lx, 0, 0}, {0, ly, 0}, {0, 0, lz}, {px, py, pz}};
}

}    // namespace

TEST(MeshFrame, JoinPiecesMovesWrappedVerticesNextToTheirNeighbours)
{
  // a strip along x from 1.6 to 2.6 in a box periodic in x with period 3: the vertices beyond
  // x = 2 were wrapped by -3
  std::vector<std::array<double, 3>> unwrapped, wrapped;
  for (int i = 0; i < 9; i++) {
    const double x = 1.6 + 0.125 * i, y = 0.1 + 0.2 * (i % 2);
    unwrapped.push_back({x, y, 0.5});
    wrapped.push_back({x > 2.0 ? x - 3.0 : x, y, 0.5});
  }
  MeshFrame f = strip(wrapped);
  join_pieces(f, orthogonal(3.0, 2.0, 1.0, true, true, false));
  for (int i = 0; i < 9; i++) {
    for (int d = 0; d < 3; d++) EXPECT_NEAR(f.x[3 * i + d], unwrapped[i][d], 1e-15 * 3) << i;
    if (wrapped[i][0] == unwrapped[i][0]) {    // not wrapped: not moved, bit for bit
      EXPECT_EQ(f.x[3 * i], wrapped[i][0]);
    }
  }
  // unwrapped already: nothing moves
  MeshFrame g = strip(unwrapped);
  join_pieces(g, orthogonal(3.0, 2.0, 1.0, true, true, false));
  EXPECT_EQ(g.x, strip(unwrapped).x);
}

TEST(MeshFrame, JoinPiecesKeepsEachPiecesFirstVertexAndNonPeriodicDirections)
{
  // two pieces: the second (vertices 3..5) has its first vertex on the far side; a long edge
  // along z, which is not periodic, stays
  MeshFrame f = strip({{0.1, 0, 0}, {0.2, 0.1, 0}, {0.1, 0.2, 0.9}});
  const MeshFrame second = strip({{2.9, 0, 0}, {0.05, 0, 0}, {2.95, 0.1, 0}});
  for (int k = 0; k < 3; k++) {
    f.ids.push_back(4 + k);
    f.x.insert(f.x.end(), second.x.begin() + 3 * k, second.x.begin() + 3 * k + 3);
  }
  f.triangles.push_back({3, 4, 5});
  f.mesh.push_back(2);
  join_pieces(f, orthogonal(3.0, 3.0, 1.0, true, true, false));
  EXPECT_EQ(f.x[3 * 2 + 2], 0.9);
  EXPECT_EQ(f.x[3 * 3], 2.9);
  EXPECT_NEAR(f.x[3 * 4], 3.05, 1e-15 * 3);
  EXPECT_EQ(f.x[3 * 5], 2.95);
}

TEST(MeshFrame, JoinPiecesInATriclinicBox)
{
  // edges a = (2, 0, 0), b = (0.5, 2, 0), c = (0.3, 0.2, 1.5), periodic along all three: a
  // triangle near the top of the box whose third vertex was wrapped by -b - c
  const BoxPeriods box = {{2, 0, 0}, {0.5, 2, 0}, {0.3, 0.2, 1.5}, {true, true, true}};
  const std::array<double, 3> third = {1.1, 2.05, 1.45};
  MeshFrame f =
      strip({{1.0, 1.9, 1.4}, {1.2, 1.95, 1.42}, {third[0] - 0.8, third[1] - 2.2, third[2] - 1.5}});
  join_pieces(f, box);
  for (int d = 0; d < 3; d++) EXPECT_NEAR(f.x[6 + d], third[d], 1e-15 * 4) << d;
}
