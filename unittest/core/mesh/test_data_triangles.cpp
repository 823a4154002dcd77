// The Mesh Triangles section of data files (fix nosb/mesh): lines parsed with the offsets of the
// read, each kind of bad line refused with the line, the section and the word named as LAMMPS's
// ValueTokenizer names it, and the corners of a triangle stored in the rows of their atoms.
#include "mesh/data_triangles.h"
#include "vertex_storage.h"

#include <gtest/gtest.h>

#include <climits>
#include <stdexcept>
#include <string>

using namespace PeriSISSM;

namespace {

std::string error_of(const std::string &text, int n = 1, long long max_id = INT_MAX)
{
  try {
    parse_data_triangles(text.c_str(), n, "Mesh Triangles", 0, 0, max_id);
  } catch (std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

}    // namespace

TEST(DataTriangles, ParsesLinesWithTheOffsetsOfTheRead)
{
  const std::string text = "1 1 0.01 1 2 3\n  2 2 2.5e-3 4 3 2   # a comment\nnot read\n";
  const auto t = parse_data_triangles(text.c_str(), 2, "Mesh Triangles", 100, 3, INT_MAX);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].mesh, 4);
  EXPECT_EQ(t[0].thickness, 0.01);
  EXPECT_EQ(t[0].v[0], 101);
  EXPECT_EQ(t[0].v[1], 102);
  EXPECT_EQ(t[0].v[2], 103);
  EXPECT_EQ(t[1].mesh, 5);
  EXPECT_EQ(t[1].thickness, 2.5e-3);
  EXPECT_EQ(t[1].v[0], 104);
  EXPECT_EQ(t[1].v[2], 102);
  EXPECT_EQ(t[1].line, "2 2 2.5e-3 4 3 2   # a comment");
}

TEST(DataTriangles, BadLinesAreNamedWithTheirSection)
{
  EXPECT_EQ(error_of("1 1 0.01 1 2\n"),
            "Fix nosb/mesh: line '1 1 0.01 1 2' of the Mesh Triangles section of the data file "
            "has 5 values instead of 6 (ID mesh thickness v1 v2 v3)");
  EXPECT_EQ(error_of("1 x 0.01 1 2 3\n"),
            "Fix nosb/mesh: invalid line '1 x 0.01 1 2 3' in the Mesh Triangles section of the "
            "data file: Not a valid integer number: 'x'");
  EXPECT_EQ(error_of("1 1 0.01q 1 2 3\n"),
            "Fix nosb/mesh: invalid line '1 1 0.01q 1 2 3' in the Mesh Triangles section of the "
            "data file: Not a valid floating-point number: '0.01q'");
  EXPECT_NE(error_of("1 1 0.01 1 2 3.0\n").find("Not a valid integer number: '3.0'"),
            std::string::npos);
  // an ID beyond the ID type (32-bit here), not beyond a 64-bit one
  EXPECT_NE(error_of("1 1 0.01 1 2 3000000000\n").find("Not a valid integer number"),
            std::string::npos);
  EXPECT_EQ(error_of("1 1 0.01 1 2 3000000000\n", 1, LLONG_MAX), "");
  EXPECT_NE(error_of("1 1 1e999 1 2 3\n").find("floating-point number: '1e999'"),
            std::string::npos);
  const std::string rule = "the mesh id must be >= 1, the thickness > 0 and the three vertex "
                           "IDs distinct";
  EXPECT_NE(error_of("1 0 0.01 1 2 3\n").find(rule), std::string::npos);
  EXPECT_NE(error_of("1 1 0 1 2 3\n").find(rule), std::string::npos);
  EXPECT_NE(error_of("1 1 nan 1 2 3\n").find(rule), std::string::npos);
  EXPECT_NE(error_of("1 1 0.01 1 2 1\n").find("'1 1 0.01 1 2 1' in the Mesh Triangles"),
            std::string::npos);
  // the first bad line counts; a missing line is the end of the file
  EXPECT_NE(error_of("1 1 0.01 1 2 3\n2 1 0.01 1\n", 2).find("'2 1 0.01 1'"), std::string::npos);
  EXPECT_EQ(error_of("1 1 0.01 1 2 3\n1 1 0.01 1 2 3", 2),
            "Unexpected end of file while reading data section Mesh Triangles");
}

TEST(DataTriangles, CornersGoToTheirRowsRotatedToStartThere)
{
  Storage<int> s(4);
  const auto a = s.arrays();
  std::unordered_set<int> rows;
  // row 0 is an atom of the deck (before first_row 1), already a vertex of mesh 1 with a
  // normal; rows 1..3 are new atoms of the read holding stale values
  s.mesh[0] = 1;
  s.ntri[0] = 1;
  s.normal[0][2] = 1.0;
  for (int i = 1; i < 4; i++) {
    s.mesh[i] = 7;
    s.ntri[i] = 5;
  }
  const int v[3] = {11, 12, 13};
  EXPECT_EQ(store_data_corner(a, 0, 11, v, 0, 1, 0.5, 1, rows, kMaxTri), DataCorner::kStored);
  EXPECT_EQ(s.ntri[0], 2);
  EXPECT_EQ(s.normal[0][2], 0.0);
  EXPECT_EQ(store_data_corner(a, 2, 13, v, 2, 1, 0.5, 1, rows, kMaxTri), DataCorner::kStored);
  EXPECT_EQ(s.mesh[2], 1);
  EXPECT_EQ(s.thickness[2], 0.5);
  EXPECT_EQ(s.owntag[2], 13);
  ASSERT_EQ(s.ntri[2], 1);    // the stale triangles are gone
  EXPECT_EQ(s.tri[2][0][0], 11);
  EXPECT_EQ(s.tri[2][0][1], 12);
  EXPECT_EQ(rows, std::unordered_set<int>({0, 2}));

  // a second triangle at row 2 adds to it; another mesh at row 0 is refused
  const int w[3] = {13, 14, 11};
  EXPECT_EQ(store_data_corner(a, 2, 13, w, 0, 1, 0.5, 1, rows, kMaxTri), DataCorner::kStored);
  EXPECT_EQ(s.ntri[2], 2);
  EXPECT_EQ(store_data_corner(a, 0, 11, w, 2, 2, 0.5, 1, rows, kMaxTri), DataCorner::kOtherMesh);
  EXPECT_EQ(s.mesh[0], 1);
  EXPECT_EQ(s.ntri[0], 2);
  EXPECT_EQ(store_data_corner(a, 2, 13, w, 0, 1, 0.5, 1, rows, 2), DataCorner::kFull);
}

TEST(DataTriangles, AHeaderLineOpensAReadThatItsLinesClose)
{
  DataSectionRead read;
  read.rows = {4};
  read.start("5 mesh triangles", 2, 30);
  EXPECT_TRUE(read.open);
  EXPECT_EQ(read.announced, 5);
  EXPECT_EQ(read.mesh_offset, 2);
  EXPECT_EQ(read.first_row, 30);
  EXPECT_TRUE(read.rows.empty());
  read.read(3);
  EXPECT_TRUE(read.open);
  read.read(2);
  EXPECT_FALSE(read.open);

  read.start("0 mesh triangles", 0, 0);
  read.read(0);    // an empty section
  EXPECT_FALSE(read.open);

  const auto error_of = [&](const std::string &line) -> std::string {
    try {
      read.start(line, 0, 0);
    } catch (std::invalid_argument &e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of(" 2.5 mesh triangles \n"),
            "Fix nosb/mesh: invalid mesh triangles line in the data file header: '2.5 mesh "
            "triangles'");
  EXPECT_NE(error_of("99999999999999999999 mesh triangles").find("invalid"), std::string::npos);
  EXPECT_NE(error_of("   ").find("invalid"), std::string::npos);
  EXPECT_EQ(error_of("-1 mesh triangles"),
            "Fix nosb/mesh: negative number of mesh triangles in the data file: '-1 mesh "
            "triangles'");
}
