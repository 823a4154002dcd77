/* PERI-SISSM core: the files of a mesh dump (dump nosb/mesh, doc/dump_nosb_mesh.rst) as text.

   - VTK XML, ASCII: PolyData (.vtp: the triangles as Polys) or UnstructuredGrid (.vtu: the
     triangles as cells of type 5); the positions as Points, each field as a PointData array
     (Float64, or Int64 for integer fields), the mesh id of each triangle as the CellData array
     "mesh", the time as the FieldData array "TimeValue".
   - a ParaView collection (.pvd) listing the frames with their times.
   - Wavefront OBJ: "v x y z" lines, then "f a b c" lines (1-based) under one "o mesh_K" line
     per mesh; OBJ holds no fields.

   Numbers are written in the shortest form that reads back to the same double.
*/
#ifndef PERISISSM_MESH_MESH_FILES_H
#define PERISISSM_MESH_MESH_FILES_H

#include "mesh/mesh_frame.h"

#include <string>
#include <vector>

namespace PeriSISSM {

enum class MeshFileFormat { kVtp, kVtu, kObj };

// Format of a dump file by its name's suffix (.vtp, .vtu or .obj). Throws std::invalid_argument
// ("file name NAME ends in none of .vtp, .vtu, .obj") for any other name.
MeshFileFormat mesh_file_format(const std::string &filename);

// a per-vertex field of a frame: its name and whether its values are integers
struct FrameField {
  std::string name;
  bool integer;
};

// Inputs: frame, fields (frame.nfields of them, in the order of the frame's values), time,
// format (kVtp or kVtu). Outputs: the file's text. Throws std::invalid_argument when the
// number of fields differs from frame.nfields or format is kObj.
std::string vtk_text(const MeshFrame &frame, const std::vector<FrameField> &fields, double time,
                     MeshFileFormat format);

// Inputs: frame, comment (one line, written after "# "). Outputs: the file's text.
std::string obj_text(const MeshFrame &frame, const std::string &comment);

// the frames of a series: time and file name (as written in the .pvd file)
struct SeriesFrame {
  double time;
  std::string file;
};

// A frame written to file: replaces the time of an entry with the same file name, else is
// appended. Inputs: series, time, file. Outputs: series.
void add_to_series(std::vector<SeriesFrame> &series, double time, const std::string &file);

// Inputs: series. Outputs: the .pvd file's text, one DataSet per frame in series order.
std::string pvd_text(const std::vector<SeriesFrame> &series);

// The series file of a frame file name: the suffix and every '*' removed, then trailing '.',
// '_' and '-' of the last path component, then ".pvd" appended ("series.pvd" when nothing of
// the component is left): "out/cloth.*.vtp" -> "out/cloth.pvd".
std::string default_series_name(const std::string &filename);

// Inputs: file (a frame file name), series (the series file name), both relative to the same
// working folder or absolute. Outputs: file's name relative to the series file's folder.
std::string name_in_series(const std::string &file, const std::string &series);

}    // namespace PeriSISSM

#endif
