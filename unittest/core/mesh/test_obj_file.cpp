// Wavefront OBJ files of read_mesh: vertex and face lines in all index forms, fans of polygons,
// relative indices, ignored lines, and an error naming the file and line for each malformed one.
#include "mesh/obj_file.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

using namespace PeriSISSM;

namespace {

// the message of the runtime_error that f throws ("" if it throws none)
template <class F> std::string error_of(F f)
{
  try {
    f();
  } catch (std::runtime_error &e) {
    return e.what();
  }
  return "";
}

std::string parse_error(const std::string &text)
{
  return error_of([&] {
    parse_obj(text, "bad.obj");
  });
}

}    // namespace

TEST(ObjFile, ReadsVerticesFacesAndTheirLines)
{
  const auto mesh = parse_obj("# a square\n"
                              "mtllib square.mtl\n"
                              "o square\n"
                              "v 0 0 0\n"
                              "v 1.5 0 0 1.0\n"            // w ignored
                              "v 1.5 2 0 0.1 0.2 0.3\n"    // colour ignored
                              "vt 0 0\n"
                              "vn 0 0 1\n"
                              "\n"
                              "v 0 2 -1e-3   # a comment\r\n"
                              "s off\n"
                              "f 1 2 3\n"
                              "f 1/1 3/1/1 4//1\n",
                              "square.obj");
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_DOUBLE_EQ(mesh.vertices[1][0], 1.5);
  EXPECT_DOUBLE_EQ(mesh.vertices[2][1], 2.0);
  EXPECT_DOUBLE_EQ(mesh.vertices[3][2], -1e-3);
  EXPECT_EQ(mesh.vertex_line, (std::vector<int>{4, 5, 6, 10}));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(mesh.triangle_line, (std::vector<int>{12, 13}));
}

TEST(ObjFile, PolygonsBecomeFansInTheirOrientation)
{
  const auto mesh =
      parse_obj("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n", "pentagon.obj");
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(mesh.triangles[2], (std::array<int, 3>{0, 3, 4}));
  EXPECT_EQ(mesh.triangle_line, (std::vector<int>{6, 6, 6}));
}

TEST(ObjFile, NegativeIndicesCountBackFromTheLastVertexReadSoFar)
{
  const auto mesh = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                              "v 1 1 0\nf -3/5 -1 -2//7\n",
                              "relative.obj");
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{1, 3, 2}));
}

TEST(ObjFile, FacesMayComeBeforeTheirVertices)
{
  const auto mesh = parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "late.obj");
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
}

TEST(ObjFile, MalformedLinesNameFileLineAndWord)
{
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  struct Case {
    std::string text;
    std::vector<std::string> expected;
  };
  const Case cases[] = {
      {"v 0 0 0\nv 1 2\n", {"bad.obj line 2", "three coordinates"}},
      {"v 0 0 0\nv 1 2 zero\n", {"bad.obj line 2", "'zero'", "not a finite number"}},
      {"v 0 0 nan\n", {"bad.obj line 1", "'nan'"}},
      {"v 1 2 3 x\n", {"bad.obj line 1", "'x'"}},
      {v3 + "f 1 2\n", {"bad.obj line 4", "at least three"}},
      {v3 + "f 1 two 3\n", {"bad.obj line 4", "'two'", "vertex index"}},
      {v3 + "f 1 0 3\n", {"bad.obj line 4", "'0'"}},
      {v3 + "f 1 2/ 3\n", {"bad.obj line 4", "'2/'"}},
      {v3 + "f 1 2/1/1/1 3\n", {"bad.obj line 4", "'2/1/1/1'"}},
      {v3 + "f 1 2//x 3\n", {"bad.obj line 4", "'2//x'"}},
      {v3 + "f 1.5 2 3\n", {"bad.obj line 4", "'1.5'"}},
      {v3 + "\nf 1 2 4\n", {"bad.obj line 5", "index 4 is out of range", "has 3 vertices"}},
      {v3 + "f 1 2 99999999999\n", {"bad.obj line 4", "'99999999999'"}},
      {v3 + "f -1 -2 -4\n", {"bad.obj line 4", "index -4", "only 3 vertices"}},
  };
  for (const auto &c : cases) {
    const std::string message = parse_error(c.text);
    for (const auto &part : c.expected)
      EXPECT_NE(message.find(part), std::string::npos) << c.text << " -> " << message;
  }
}
