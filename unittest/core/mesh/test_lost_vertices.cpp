// Triangles that lost a vertex (fix nosb/mesh at init): corners held here are checked here
// (same mesh or dropped), the others asked once of the caller's function as (ID, mesh id)
// pairs in order, and each answer drops or keeps the triangle; the answering side's lookup.
#include "mesh/lost_vertices.h"
#include "vertex_storage.h"

#include <gtest/gtest.h>

#include <map>
#include <vector>

using namespace PeriSISSM;

namespace {

void set_triangles(Storage<long> &s, int i, int mesh, const std::vector<std::array<long, 2>> &t)
{
  s.mesh[i] = mesh;
  s.ntri[i] = (int) t.size();
  for (size_t k = 0; k < t.size(); k++) {
    s.tri[i][k][0] = t[k][0];
    s.tri[i][k][1] = t[k][1];
  }
}

}    // namespace

TEST(LostVertices, LocalCornersAreCheckedHereTheOthersAskedInOrder)
{
  // rows: 0 (ID 1, mesh 1) and 1 (ID 2, mesh 1) owned, 2 (ID 3, mesh 2) a ghost of another
  // mesh, 3 (ID 4) a ghost of no mesh; IDs 10, 11, 12 are not here
  Storage<long> s(4);
  const std::map<long, int> rows = {{1, 0}, {2, 1}, {3, 2}, {4, 3}};
  auto local = [&](long id) {
    auto it = rows.find(id);
    return it == rows.end() ? -1 : it->second;
  };
  set_triangles(s, 0, 1, {{2, 10}, {3, 2}, {11, 12}});
  set_triangles(s, 1, 1, {{1, 11}, {4, 1}});
  s.mesh[2] = 2;

  std::vector<long> asked;
  int calls = 0;
  auto exists = [&](const std::vector<long> &pairs) {
    calls++;
    asked = pairs;
    // 10 and 12 exist in mesh 1 elsewhere, 11 does not
    std::vector<int> found;
    for (size_t k = 0; k < pairs.size(); k += 2) found.push_back(pairs[k] != 11);
    return found;
  };
  drop_lost_triangles(s.arrays(), 2, local, exists);

  EXPECT_EQ(calls, 1);
  const std::vector<long> expect_asked = {10, 1, 11, 1, 12, 1, 11, 1};
  EXPECT_EQ(asked, expect_asked);
  // row 0: (2, 10) kept; (3, 2) has a vertex of mesh 2; (11, 12) lost 11
  ASSERT_EQ(s.ntri[0], 1);
  EXPECT_EQ(s.tri[0][0][0], 2);
  EXPECT_EQ(s.tri[0][0][1], 10);
  // row 1: (1, 11) lost 11; (4, 1) has a vertex of no mesh
  EXPECT_EQ(s.ntri[1], 0);
}

TEST(LostVertices, NothingToAskStillCallsOnceAndKeepsCompleteTriangles)
{
  Storage<int> s(3);
  s.mesh[0] = s.mesh[1] = s.mesh[2] = 5;
  s.ntri[0] = 1;
  s.tri[0][0][0] = 2;
  s.tri[0][0][1] = 3;
  auto local = [](int id) {
    return id >= 1 && id <= 3 ? id - 1 : -1;
  };
  int calls = 0;
  auto exists = [&](const std::vector<int> &pairs) {
    calls++;
    EXPECT_TRUE(pairs.empty());
    return std::vector<int>();
  };
  drop_lost_triangles(s.arrays(), 1, local, exists);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(s.ntri[0], 1);
  EXPECT_EQ(s.tri[0][0][1], 3);
}

TEST(LostVertices, OwnedVerticesAnswerOnlyForOwnedAtomsOfTheSameMesh)
{
  // rows 0, 1 owned (IDs 7 and 8, meshes 1 and 2), row 2 a ghost (ID 9, mesh 1)
  const int mesh[3] = {1, 2, 1};
  auto local = [](long id) {
    return id >= 7 && id <= 9 ? (int) id - 7 : -1;
  };
  const std::vector<long> pairs = {7, 1, 8, 1, 8, 2, 9, 1, 42, 1};
  const std::vector<int> expect = {1, 0, 1, 0, 0};
  EXPECT_EQ(owned_vertices(pairs, 2, local, mesh), expect);
}
