// The files of a mesh dump as text: VTK XML PolyData and UnstructuredGrid, OBJ, the .pvd series,
// the format by suffix, the series file's default name and the frames' names in it.
#include "mesh/mesh_files.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace PeriSISSM;

namespace {

// two triangles of mesh 1 over atoms 10, 20, 30, 40 and one of mesh 3 over 20, 30, 50 at
// (ID / 10, -ID / 1e20, 1e300) (quotients of exact doubles: the doubles nearest the printed
// values); fields vx (ID / 3) and an integer field
MeshFrame sample_frame()
{
  std::vector<double> rows;
  for (long long id : {10, 20, 30, 40, 50})
    rows.insert(rows.end(), {(double) id, id / 10.0, -id / 1e20, 1e300, id / 3.0, 2.0});
  return assemble_frame(rows, 6, {{1, {10, 20, 30}}, {1, {10, 30, 40}}, {3, {20, 50, 30}}});
}

const std::vector<FrameField> kFields = {{"vx", false}, {"c_s[1]<&>", true}};

// the lines of text between the line holding start and the next line holding "</DataArray>"
std::vector<std::string> array_lines(const std::string &text, const std::string &start)
{
  std::vector<std::string> lines;
  std::istringstream in(text.substr(text.find(start)));
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line) && line.find("</DataArray>") == std::string::npos)
    lines.push_back(line.substr(line.find_first_not_of(' ')));
  return lines;
}

}    // namespace

TEST(MeshFiles, FormatBySuffix)
{
  EXPECT_EQ(mesh_file_format("a/cloth.*.vtp"), MeshFileFormat::kVtp);
  EXPECT_EQ(mesh_file_format("cloth.vtu"), MeshFileFormat::kVtu);
  EXPECT_EQ(mesh_file_format("cloth.*.obj"), MeshFileFormat::kObj);
  for (const char *bad : {"cloth.vtk", "cloth", "cloth.vtp.gz", "vtp"}) {
    try {
      mesh_file_format(bad);
      FAIL() << bad;
    } catch (std::invalid_argument &e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("file name ") + bad + " ends in none of .vtp, .vtu, .obj");
    }
  }
}

TEST(MeshFiles, PolyDataHoldsPointsPolysFieldsMeshAndTime)
{
  const std::string t = vtk_text(sample_frame(), kFields, 0.25, MeshFileFormat::kVtp);
  EXPECT_NE(t.find("<VTKFile type=\"PolyData\""), std::string::npos);
  EXPECT_NE(t.find("<Piece NumberOfPoints=\"5\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
                   "NumberOfStrips=\"0\" NumberOfPolys=\"3\">"),
            std::string::npos);
  EXPECT_EQ(array_lines(t, "Name=\"TimeValue\""), (std::vector<std::string>{"0.25"}));
  EXPECT_EQ(array_lines(t, "NumberOfComponents=\"3\""),
            (std::vector<std::string>{"1 -1e-19 1e+300", "2 -2e-19 1e+300", "3 -3e-19 1e+300",
                                      "4 -4e-19 1e+300", "5 -5e-19 1e+300"}));
  EXPECT_EQ(array_lines(t, "Name=\"connectivity\""),
            (std::vector<std::string>{"0 1 2", "0 2 3", "1 4 2"}));
  EXPECT_EQ(array_lines(t, "Name=\"offsets\""), (std::vector<std::string>{"3", "6", "9"}));
  EXPECT_EQ(array_lines(t, "Name=\"mesh\""), (std::vector<std::string>{"1", "1", "3"}));
  EXPECT_EQ(t.find("Name=\"types\""), std::string::npos);
  EXPECT_NE(t.find("<Polys>"), std::string::npos);
  // fields: shortest round-trip numbers, integers as Int64, names escaped
  const auto vx = array_lines(t, "Name=\"vx\"");
  ASSERT_EQ(vx.size(), 5u);
  EXPECT_EQ(std::strtod(vx[0].c_str(), nullptr), 10 / 3.0);
  EXPECT_EQ(vx[0], "3.3333333333333335");
  EXPECT_NE(t.find("type=\"Int64\" Name=\"c_s[1]&lt;&amp;&gt;\""), std::string::npos);
  EXPECT_EQ(array_lines(t, "Name=\"c_s[1]&lt;"),
            (std::vector<std::string>{"2", "2", "2", "2", "2"}));
}

TEST(MeshFiles, UnstructuredGridHoldsTheSameArraysAsCellsOfTriangles)
{
  const MeshFrame f = sample_frame();
  const std::string p = vtk_text(f, kFields, 0.25, MeshFileFormat::kVtp);
  const std::string u = vtk_text(f, kFields, 0.25, MeshFileFormat::kVtu);
  EXPECT_NE(u.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
  EXPECT_NE(u.find("<Piece NumberOfPoints=\"5\" NumberOfCells=\"3\">"), std::string::npos);
  EXPECT_NE(u.find("<Cells>"), std::string::npos);
  EXPECT_EQ(array_lines(u, "Name=\"types\""), (std::vector<std::string>{"5", "5", "5"}));
  for (const char *a : {"Name=\"connectivity\"", "Name=\"offsets\"", "Name=\"vx\"",
                        "NumberOfComponents=\"3\"", "Name=\"mesh\""})
    EXPECT_EQ(array_lines(u, a), array_lines(p, a)) << a;
}

TEST(MeshFiles, VtkRejectsAWrongNumberOfFieldNamesAndObj)
{
  EXPECT_THROW(vtk_text(sample_frame(), {{"vx", false}}, 0, MeshFileFormat::kVtp),
               std::invalid_argument);
  EXPECT_THROW(vtk_text(sample_frame(), kFields, 0, MeshFileFormat::kObj), std::invalid_argument);
}

TEST(MeshFiles, ObjHoldsVerticesAndOneBasedFacesPerMesh)
{
  EXPECT_EQ(obj_text(sample_frame(), "step 7"),
            "# step 7\n"
            "v 1 -1e-19 1e+300\nv 2 -2e-19 1e+300\nv 3 -3e-19 1e+300\nv 4 -4e-19 1e+300\n"
            "v 5 -5e-19 1e+300\n"
            "o mesh_1\nf 1 2 3\nf 1 3 4\n"
            "o mesh_3\nf 2 5 3\n");
  MeshFrame empty;
  EXPECT_EQ(obj_text(empty, "none"), "# none\n");
}

TEST(MeshFiles, SeriesReplacesARewrittenFrameAndListsTheOthersInOrder)
{
  std::vector<SeriesFrame> s;
  add_to_series(s, 0.0, "c.0.vtp");
  add_to_series(s, 0.5, "c.10.vtp");
  add_to_series(s, 0.0625, "c.0.vtp");    // step 0 written again (a second run)
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(pvd_text(s),
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0.0625\" part=\"0\" file=\"c.0.vtp\"/>\n"
            "    <DataSet timestep=\"0.5\" part=\"0\" file=\"c.10.vtp\"/>\n"
            "  </Collection>\n</VTKFile>\n");
  EXPECT_EQ(pvd_text({}),
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
            "  <Collection>\n  </Collection>\n</VTKFile>\n");
}

TEST(MeshFiles, DefaultSeriesName)
{
  EXPECT_EQ(default_series_name("cloth.*.vtp"), "cloth.pvd");
  EXPECT_EQ(default_series_name("out/cloth_*.vtu"), "out/cloth.pvd");
  EXPECT_EQ(default_series_name("cloth.vtp"), "cloth.pvd");
  EXPECT_EQ(default_series_name("out/*.vtp"), "out/series.pvd");
  EXPECT_EQ(default_series_name("a.b/frame*-x.vtp"), "a.b/frame-x.pvd");
}

TEST(MeshFiles, FrameNamesRelativeToTheSeriesFolder)
{
  EXPECT_EQ(name_in_series("cloth.10.vtp", "cloth.pvd"), "cloth.10.vtp");
  EXPECT_EQ(name_in_series("out/cloth.10.vtp", "out/cloth.pvd"), "cloth.10.vtp");
  EXPECT_EQ(name_in_series("out/f/c.1.vtp", "out/c.pvd"), "f/c.1.vtp");
  EXPECT_EQ(name_in_series("frames/c.1.vtp", "series/c.pvd"), "../frames/c.1.vtp");
  EXPECT_EQ(name_in_series("/tmp/x/c.1.vtp", "/tmp/x/./c.pvd"), "c.1.vtp");
}
