// Per-atom records of mesh vertices (fix nosb/mesh): the exchange and border layouts field by
// field, round trips for 32- and 64-bit IDs (IDs beyond 2^53 exactly), non-mesh rows, copies,
// dropping triangles that lost a vertex, the one corner that writes a triangle, the rotation of
// a triangle to start at its vertex, the vertex normal with a missing vertex, the triangles
// written to data files and the per-atom output.
#include "mesh/mesh_geometry.h"
#include "mesh/vertex_records.h"
#include "vertex_storage.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

using namespace PeriSISSM;

namespace {

// row i: mesh 3, thickness 0.01, owntag, a normal, three triangles
template <class Id> void fill(Storage<Id> &s, int i, Id own, Id base)
{
  s.mesh[i] = 3;
  s.thickness[i] = 0.01;
  s.owntag[i] = own;
  s.normal[i][0] = 0.6;
  s.normal[i][1] = -0.8;
  s.normal[i][2] = 0.0;
  s.ntri[i] = 3;
  for (int k = 0; k < 3; k++) {
    s.tri[i][k][0] = base + 2 * k;
    s.tri[i][k][1] = base + 2 * k + 1;
  }
}

template <class Id> void expect_same_row(Storage<Id> &s, int i, int j, bool with_owntag)
{
  EXPECT_EQ(s.mesh[j], s.mesh[i]);
  EXPECT_EQ(s.thickness[j], s.thickness[i]);
  if (with_owntag) { EXPECT_EQ(s.owntag[j], s.owntag[i]); }
  for (int d = 0; d < 3; d++) EXPECT_EQ(s.normal[j][d], s.normal[i][d]);
  ASSERT_EQ(s.ntri[j], s.ntri[i]);
  for (int k = 0; k < s.ntri[i]; k++) {
    EXPECT_EQ(s.tri[j][k][0], s.tri[i][k][0]);
    EXPECT_EQ(s.tri[j][k][1], s.tri[i][k][1]);
  }
}

template <class Id> void round_trip(Id own, Id base)
{
  Storage<Id> s(3);
  fill(s, 0, own, base);
  const auto a = s.arrays();
  std::vector<double> buf(kVertexScalars + 2 * kMaxTri, -1.0);
  const int m = pack_vertex(a, 0, buf.data());
  EXPECT_EQ(m, vertex_record_size(3, 3));
  EXPECT_EQ(unpack_vertex(a, 2, buf.data()), m);
  expect_same_row(s, 0, 2, true);

  const int mb = pack_vertex(a, 0, buf.data(), VertexRecord::kBorder);
  EXPECT_EQ(mb, kVertexBorderScalars + 6);
  s.owntag[1] = 77;
  EXPECT_EQ(unpack_vertex(a, 1, buf.data(), VertexRecord::kBorder), mb);
  expect_same_row(s, 0, 1, false);
  EXPECT_EQ(s.owntag[1], (Id) 77);    // ghosts keep their owntag
}

}    // namespace

TEST(VertexRecords, IdBitsAreThoseOfTheIdAsA64BitInteger)
{
  for (int64_t id : {int64_t(1), int64_t(123456789), (int64_t(1) << 53) + 1, INT64_MAX}) {
    const double d = id_bits(id);
    int64_t back;
    std::memcpy(&back, &d, sizeof(back));
    EXPECT_EQ(back, id);
    EXPECT_EQ(bits_id<int64_t>(d), id);
  }
  // a 32-bit ID carries the bits of the same value as a 64-bit one
  const double d32 = id_bits(int(2147483647)), d64 = id_bits(int64_t(2147483647));
  EXPECT_EQ(std::memcmp(&d32, &d64, sizeof(double)), 0);
  EXPECT_EQ(bits_id<int>(d32), 2147483647);
}

TEST(VertexRecords, ExchangeLayoutFieldByField)
{
  Storage<int64_t> s(1);
  fill<int64_t>(s, 0, 41, int64_t(1) << 40);
  double buf[kVertexScalars + 2 * kMaxTri];
  ASSERT_EQ(pack_vertex(s.arrays(), 0, buf), kVertexScalars + 6);
  EXPECT_EQ(buf[0], 3.0);
  EXPECT_EQ(buf[1], 0.01);
  EXPECT_EQ(bits_id<int64_t>(buf[2]), 41);
  EXPECT_EQ(buf[3], 0.6);
  EXPECT_EQ(buf[4], -0.8);
  EXPECT_EQ(buf[5], 0.0);
  EXPECT_EQ(buf[6], 3.0);
  for (int k = 0; k < 6; k++) EXPECT_EQ(bits_id<int64_t>(buf[7 + k]), (int64_t(1) << 40) + k);

  ASSERT_EQ(pack_vertex(s.arrays(), 0, buf, VertexRecord::kBorder), kVertexBorderScalars + 6);
  EXPECT_EQ(buf[0], 3.0);
  EXPECT_EQ(buf[1], 0.01);
  EXPECT_EQ(buf[2], 0.6);
  EXPECT_EQ(buf[5], 3.0);
  for (int k = 0; k < 6; k++) EXPECT_EQ(bits_id<int64_t>(buf[6 + k]), (int64_t(1) << 40) + k);
}

TEST(VertexRecords, RoundTripsWith32And64BitIds)
{
  round_trip<int>(5, 2147483000);
  round_trip<int64_t>((int64_t(1) << 53) + 3, (int64_t(1) << 60) + 1);
}

TEST(VertexRecords, NonMeshRowIsOneZeroAndClearsTheRow)
{
  Storage<int> s(2);
  fill(s, 1, 9, 100);
  double buf[kVertexScalars + 2 * kMaxTri];
  EXPECT_EQ(pack_vertex(s.arrays(), 0, buf), 1);
  EXPECT_EQ(buf[0], 0.0);
  EXPECT_EQ(vertex_record_size(0, 0), 1);
  EXPECT_EQ(unpack_vertex(s.arrays(), 1, buf), 1);
  EXPECT_EQ(s.mesh[1], 0);
  EXPECT_EQ(s.thickness[1], 0.0);
  EXPECT_EQ(s.ntri[1], 0);
  EXPECT_EQ(s.owntag[1], 0);
  for (int d = 0; d < 3; d++) EXPECT_EQ(s.normal[1][d], 0.0);

  fill(s, 1, 9, 100);
  EXPECT_EQ(pack_vertex(s.arrays(), 0, buf, VertexRecord::kBorder), 1);
  EXPECT_EQ(unpack_vertex(s.arrays(), 1, buf, VertexRecord::kBorder), 1);
  EXPECT_EQ(s.mesh[1], 0);
  EXPECT_EQ(s.thickness[1], 0.0);
  EXPECT_EQ(s.ntri[1], 0);
  EXPECT_EQ(s.owntag[1], 9);    // ghosts keep their owntag
  for (int d = 0; d < 3; d++) EXPECT_EQ(s.normal[1][d], 0.0);
}

TEST(VertexRecords, CopyAndClear)
{
  Storage<int> s(2);
  fill(s, 0, 4, 10);
  copy_vertex(s.arrays(), 0, 1);
  expect_same_row(s, 0, 1, true);
  clear_vertex(s.arrays(), 0);
  EXPECT_EQ(s.mesh[0], 0);
  EXPECT_EQ(s.thickness[0], 0.0);
  EXPECT_EQ(s.ntri[0], 0);
  EXPECT_EQ(s.owntag[0], 0);
  for (int d = 0; d < 3; d++) EXPECT_EQ(s.normal[0][d], 0.0);
}

TEST(VertexRecords, TrianglesThatLostAVertexAreDroppedInOrder)
{
  Storage<int> s(1);
  const int pairs[5][2] = {{2, 3}, {0, 4}, {4, 5}, {5, 0}, {6, 7}};
  s.mesh[0] = 1;
  s.ntri[0] = 5;
  for (int k = 0; k < 5; k++) {
    s.tri[0][k][0] = pairs[k][0];
    s.tri[0][k][1] = pairs[k][1];
  }
  EXPECT_EQ(keep_complete_triangles(s.arrays(), 0), 3);
  EXPECT_EQ(s.ntri[0], 3);
  const int kept[3][2] = {{2, 3}, {4, 5}, {6, 7}};
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(s.tri[0][k][0], kept[k][0]);
    EXPECT_EQ(s.tri[0][k][1], kept[k][1]);
  }
}

TEST(VertexRecords, EachTriangleIsWrittenByExactlyOneCorner)
{
  // every corner of a triangle stores it rotated to start at itself
  const int triangles[4][3] = {{1, 2, 3}, {3, 2, 1}, {7, 5, 9}, {100, 4, 50}};
  for (const auto &t : triangles) {
    int writers = 0, writer = 0;
    for (int c = 0; c < 3; c++) {
      if (writes_triangle(t[c], t[(c + 1) % 3], t[(c + 2) % 3])) {
        writers++;
        writer = t[c];
      }
    }
    EXPECT_EQ(writers, 1);
    EXPECT_EQ(writer, std::min(t[0], std::min(t[1], t[2])));
  }
}

TEST(VertexRecords, AddCornerRotatesToStartAtTheVertexAndStopsAtTheLimit)
{
  Storage<int> s(1);
  const int v[3] = {10, 20, 30};
  ASSERT_TRUE(add_corner(s.arrays(), 0, v, 0, kMaxTri));
  ASSERT_TRUE(add_corner(s.arrays(), 0, v, 1, kMaxTri));
  ASSERT_TRUE(add_corner(s.arrays(), 0, v, 2, kMaxTri));
  EXPECT_EQ(s.ntri[0], 3);
  const int expect[3][2] = {{20, 30}, {30, 10}, {10, 20}};    // same orientation each time
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(s.tri[0][k][0], expect[k][0]);
    EXPECT_EQ(s.tri[0][k][1], expect[k][1]);
  }
  s.ntri[0] = kMaxTri;
  EXPECT_FALSE(add_corner(s.arrays(), 0, v, 0, kMaxTri));
  EXPECT_EQ(s.ntri[0], kMaxTri);
}

TEST(VertexRecords, VertexNormalSkipsTrianglesWithAMissingVertex)
{
  // vertex 1 at the origin; a fan of three triangles; vertex 5 is not found
  std::map<int, std::array<double, 3>> x = {
      {1, {0, 0, 0}}, {2, {1, 0, 0}}, {3, {0, 1, 0.5}}, {4, {-1, 0, 0}}};
  auto position = [&](int id) -> const double * {
    auto it = x.find(id);
    return it == x.end() ? nullptr : it->second.data();
  };
  std::vector<int> r0 = {2, 3}, r1 = {3, 4}, r2 = {4, 5};
  int *tri[3] = {r0.data(), r1.data(), r2.data()};

  double expected[3] = {0.0, 0.0, 0.0};
  add_angle_weighted_normal(x[1].data(), x[2].data(), x[3].data(), expected);
  add_angle_weighted_normal(x[1].data(), x[3].data(), x[4].data(), expected);
  normalize_or_zero(expected);

  double n[3] = {9, 9, 9};
  EXPECT_EQ(vertex_normal(x[1].data(), 3, tri, position, n), 5);
  for (int d = 0; d < 3; d++) EXPECT_EQ(n[d], expected[d]);
  EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-15);

  // the first missing one is named; with none found the normal is zero
  std::vector<int> r3 = {6, 2};
  int *tri2[2] = {r3.data(), r2.data()};
  EXPECT_EQ(vertex_normal(x[1].data(), 2, tri2, position, n), 6);
  for (int d = 0; d < 3; d++) EXPECT_EQ(n[d], 0.0);
  EXPECT_EQ(vertex_normal(x[1].data(), 2, tri, position, n), 0);
}

TEST(VertexRecords, MissingNormalsAreFilledOnlyWhereAllThreeAreZero)
{
  Storage<int> s(4);
  s.mesh[0] = s.mesh[1] = s.mesh[3] = 1;    // row 2 is no mesh vertex
  s.normal[1][2] = 1.0;                     // row 1 has a normal
  s.normal[3][0] = -0.0;                    // a negative zero counts as zero
  EXPECT_TRUE(lacks_normal(s.arrays(), 0));
  EXPECT_FALSE(lacks_normal(s.arrays(), 1));
  EXPECT_FALSE(lacks_normal(s.arrays(), 2));
  EXPECT_TRUE(lacks_normal(s.arrays(), 3));
  double rows[4][3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0.6, 0.8, 0}};
  double *n[4] = {rows[0], rows[1], rows[2], rows[3]};
  EXPECT_EQ(fill_missing_normals(s.arrays(), 3, n), 1);    // row 3 is beyond nrows
  EXPECT_EQ(s.normal[0][2], 1.0);
  EXPECT_EQ(s.normal[1][1], 0.0);
  EXPECT_EQ(s.normal[1][2], 1.0);
  for (int d = 0; d < 3; d++) EXPECT_EQ(s.normal[2][d], 0.0);
  EXPECT_EQ(fill_missing_normals(s.arrays(), 4, n), 1);
  EXPECT_EQ(s.normal[3][1], 0.8);
}

TEST(VertexRecords, WrittenTrianglesAreCountedAndPackedOnceFromTheirSmallestId)
{
  // the square 1-2-3-4 as triangles (1 2 3) and (1 3 4), every corner storing its triangles;
  // row 4 is a plain atom; 64-bit IDs beyond 2^53 for vertex 4
  using Id = int64_t;
  const Id big = (Id(1) << 60) + 1;
  const Id tag[5] = {1, 2, 3, big, 9};
  const Id triangles[2][3] = {{1, 2, 3}, {1, 3, big}};
  Storage<Id> s(5);
  const auto a = s.arrays();
  for (const auto &t : triangles)
    for (int c = 0; c < 3; c++) {
      const int i = t[c] == big ? 3 : (int) t[c] - 1;
      s.mesh[i] = 2;
      s.thickness[i] = 0.25;
      ASSERT_TRUE(add_corner(a, i, t, c, kMaxTri));
    }
  EXPECT_EQ(count_written_triangles(a, 5, tag), 2);
  EXPECT_EQ(count_written_triangles(a, 1, tag), 2);    // row 0 (ID 1) writes both
  EXPECT_EQ(count_written_triangles(a, 0, tag), 0);

  std::vector<std::array<double, 5>> rows(4);
  double *buf[4] = {rows[0].data(), rows[1].data(), rows[2].data(), rows[3].data()};
  ASSERT_EQ(pack_written_triangles(a, 5, tag, buf), 2);
  for (int n = 0; n < 2; n++) {
    EXPECT_EQ(buf[n][0], 2.0);
    EXPECT_EQ(buf[n][1], 0.25);
    for (int c = 0; c < 3; c++) EXPECT_EQ(bits_id<Id>(buf[n][2 + c]), triangles[n][c]);
  }
}

TEST(VertexRecords, OutputRowIsMeshThicknessTrianglesAndNormal)
{
  Storage<int> s(1);
  fill(s, 0, 5, 10);
  double out[kVertexOutputs];
  output_row(s.arrays(), 0, out);
  const double expect[kVertexOutputs] = {3.0, 0.01, 3.0, 0.6, -0.8, 0.0};
  for (int c = 0; c < kVertexOutputs; c++) EXPECT_EQ(out[c], expect[c]);
}

TEST(VertexRecords, BorderRecordsOfAListGoOneAfterTheOtherIntoConsecutiveRows)
{
  // rows 0 and 2 are mesh vertices, row 1 is not; list 2, 1, 0 into rows 3, 4, 5
  Storage<int> s(6);
  fill(s, 0, 5, 10);
  fill(s, 2, 6, 20);
  s.ntri[2] = 1;
  for (int i = 3; i < 6; i++) s.mesh[i] = 9;
  const int list[3] = {2, 1, 0};
  std::vector<double> buf(3 * (kVertexScalars + 2 * kMaxTri), -1.0);
  const auto a = s.arrays();
  const int m = pack_vertices(a, 3, list, buf.data(), VertexRecord::kBorder);
  EXPECT_EQ(m, (kVertexBorderScalars + 2) + 1 + (kVertexBorderScalars + 6));
  EXPECT_EQ(unpack_vertices(a, 3, 3, buf.data(), VertexRecord::kBorder), m);
  expect_same_row(s, 2, 3, false);
  EXPECT_EQ(s.mesh[4], 0);
  expect_same_row(s, 0, 5, false);
}
