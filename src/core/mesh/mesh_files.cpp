/* PERI-SISSM core: the files of a mesh dump as text (mesh/mesh_files.h). */
#include "mesh/mesh_files.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace PeriSISSM {

namespace {

  bool ends_with(const std::string &s, const std::string &tail)
  {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  }

  // shortest text that reads back to the same double
  std::string number(double v)
  {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, r.ptr);
  }

  std::string xml_escaped(const std::string &s)
  {
    std::string out;
    for (char c : s) {
      switch (c) {
        case '&':
          out += "&amp;";
          break;
        case '<':
          out += "&lt;";
          break;
        case '>':
          out += "&gt;";
          break;
        case '"':
          out += "&quot;";
          break;
        case '\'':
          out += "&apos;";
          break;
        default:
          out += c;
      }
    }
    return out;
  }

  // one DataArray element: head is everything after "<DataArray ", body its lines
  void data_array(std::string &out, const std::string &indent, const std::string &head,
                  const std::string &body)
  {
    out +=
        indent + "<DataArray " + head + " format=\"ascii\">\n" + body + indent + "</DataArray>\n";
  }

}    // namespace

MeshFileFormat mesh_file_format(const std::string &filename)
{
  if (ends_with(filename, ".vtp")) return MeshFileFormat::kVtp;
  if (ends_with(filename, ".vtu")) return MeshFileFormat::kVtu;
  if (ends_with(filename, ".obj")) return MeshFileFormat::kObj;
  throw std::invalid_argument("file name " + filename + " ends in none of .vtp, .vtu, .obj");
}

std::string vtk_text(const MeshFrame &frame, const std::vector<FrameField> &fields, double time,
                     MeshFileFormat format)
{
  if ((int) fields.size() != frame.nfields)
    throw std::invalid_argument("vtk_text: " + std::to_string(fields.size()) + " field names for " +
                                std::to_string(frame.nfields) + " fields");
  if (format == MeshFileFormat::kObj) throw std::invalid_argument("vtk_text: OBJ is no VTK file");
  const bool poly = format == MeshFileFormat::kVtp;
  const std::string grid = poly ? "PolyData" : "UnstructuredGrid";
  const size_t nv = frame.ids.size(), nt = frame.triangles.size();
  const std::string in3 = "      ", in4 = "        ";

  std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + grid +
      "\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <" + grid + ">\n";
  out += "    <FieldData>\n";
  data_array(out, in3, "type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\"",
             in4 + number(time) + "\n");
  out += "    </FieldData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(nv) + "\" ";
  if (poly)
    out += "NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
        std::to_string(nt) + "\">\n";
  else
    out += "NumberOfCells=\"" + std::to_string(nt) + "\">\n";

  out += in3 + "<PointData>\n";
  for (int f = 0; f < frame.nfields; f++) {
    std::string body;
    for (size_t i = 0; i < nv; i++) {
      const double v = frame.fields[i * frame.nfields + f];
      body += in4 + (fields[f].integer ? std::to_string(std::llround(v)) : number(v)) + "\n";
    }
    data_array(out, in4,
               std::string("type=\"") + (fields[f].integer ? "Int64" : "Float64") + "\" Name=\"" +
                   xml_escaped(fields[f].name) + "\"",
               body);
  }
  out += in3 + "</PointData>\n";

  std::string mesh;
  for (int m : frame.mesh) mesh += in4 + std::to_string(m) + "\n";
  out += in3 + "<CellData>\n";
  data_array(out, in4, "type=\"Int32\" Name=\"mesh\"", mesh);
  out += in3 + "</CellData>\n";

  std::string points;
  for (size_t i = 0; i < nv; i++)
    points += in4 + number(frame.x[3 * i]) + " " + number(frame.x[3 * i + 1]) + " " +
        number(frame.x[3 * i + 2]) + "\n";
  out += in3 + "<Points>\n";
  data_array(out, in4, "type=\"Float64\" NumberOfComponents=\"3\"", points);
  out += in3 + "</Points>\n";

  std::string connectivity, offsets, types;
  for (size_t t = 0; t < nt; t++) {
    const auto &c = frame.triangles[t];
    connectivity +=
        in4 + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
    offsets += in4 + std::to_string(3 * (t + 1)) + "\n";
    types += in4 + "5\n";    // VTK_TRIANGLE
  }
  const std::string cells = poly ? "Polys" : "Cells";
  out += in3 + "<" + cells + ">\n";
  data_array(out, in4, "type=\"Int64\" Name=\"connectivity\"", connectivity);
  data_array(out, in4, "type=\"Int64\" Name=\"offsets\"", offsets);
  if (!poly) data_array(out, in4, "type=\"UInt8\" Name=\"types\"", types);
  out += in3 + "</" + cells + ">\n";
  out += "    </Piece>\n  </" + grid + ">\n</VTKFile>\n";
  return out;
}

std::string obj_text(const MeshFrame &frame, const std::string &comment)
{
  std::string out = "# " + comment + "\n";
  for (size_t i = 0; i < frame.ids.size(); i++)
    out += "v " + number(frame.x[3 * i]) + " " + number(frame.x[3 * i + 1]) + " " +
        number(frame.x[3 * i + 2]) + "\n";
  for (size_t t = 0; t < frame.triangles.size(); t++) {
    if (t == 0 || frame.mesh[t] != frame.mesh[t - 1])
      out += "o mesh_" + std::to_string(frame.mesh[t]) + "\n";
    const auto &c = frame.triangles[t];
    out += "f " + std::to_string(c[0] + 1) + " " + std::to_string(c[1] + 1) + " " +
        std::to_string(c[2] + 1) + "\n";
  }
  return out;
}

void add_to_series(std::vector<SeriesFrame> &series, double time, const std::string &file)
{
  for (SeriesFrame &s : series)
    if (s.file == file) {
      s.time = time;
      return;
    }
  series.push_back({time, file});
}

std::string pvd_text(const std::vector<SeriesFrame> &series)
{
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const SeriesFrame &s : series)
    out += "    <DataSet timestep=\"" + number(s.time) + "\" part=\"0\" file=\"" +
        xml_escaped(s.file) + "\"/>\n";
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

std::string default_series_name(const std::string &filename)
{
  std::string name = filename;
  const size_t dot = name.rfind('.');
  const size_t slash = name.rfind('/');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) name.resize(dot);
  std::string folder, base;
  if (slash != std::string::npos && slash < name.size()) {
    folder = name.substr(0, slash + 1);
    base = name.substr(slash + 1);
  } else {
    base = name;
  }
  std::string kept;
  for (char c : base)
    if (c != '*') kept += c;
  while (!kept.empty() && (kept.back() == '.' || kept.back() == '_' || kept.back() == '-'))
    kept.pop_back();
  return folder + (kept.empty() ? "series" : kept) + ".pvd";
}

std::string name_in_series(const std::string &file, const std::string &series)
{
  namespace fs = std::filesystem;
  const fs::path f = fs::absolute(file).lexically_normal();
  const fs::path folder = fs::absolute(series).lexically_normal().parent_path();
  return f.lexically_relative(folder).generic_string();
}

}    // namespace PeriSISSM
