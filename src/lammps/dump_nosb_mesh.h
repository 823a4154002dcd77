/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   dump ID group-ID nosb/mesh N file [field ...] [pvd yes|no|FILE]: the triangles of the meshes
   of read_mesh whose three vertices are in the group, with per-vertex fields named as dump
   custom names them, as VTK XML (.vtp, .vtu; plus a .pvd series) or Wavefront OBJ (.obj) files,
   one per frame, written by rank 0 (doc/dump_nosb_mesh.rst; the files: core mesh/mesh_files.h).
------------------------------------------------------------------------- */

#ifdef DUMP_CLASS
// clang-format off
DumpStyle(nosb/mesh,DumpNosbMesh);
// clang-format on
#else

#ifndef LMP_DUMP_NOSB_MESH_H
#define LMP_DUMP_NOSB_MESH_H

#include "dump_custom.h"

#include "mesh/mesh_files.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

// The arguments dump custom parses for dump nosb/mesh: ID, group, style, N, file, then "id xu
// yu zu" (the vertex rows' head: ID and unwrapped position) and the user's fields; the
// keywords after the fields apart. A base of DumpNosbMesh placed before DumpCustom, so that
// the words outlive DumpCustom's constructor, which may keep pointers to them.
struct DumpNosbMeshArgs {
  DumpNosbMeshArgs(int narg, char **arg);
  std::vector<std::string> words;       // what DumpCustom gets
  std::vector<char *> argv;             // pointers into words
  std::vector<std::string> keywords;    // keyword value pairs after the fields
};

class DumpNosbMesh : private DumpNosbMeshArgs, public DumpCustom {
 public:
  DumpNosbMesh(class LAMMPS *, int, char **);

 protected:
  void init_style() override;
  void openfile() override;
  int count() override;
  void pack(tagint *) override;
  void write_header(bigint) override {}
  void write_data(int, double *) override {}
  void write_footer() override;

  PeriSISSM::MeshFileFormat format;
  std::vector<PeriSISSM::FrameField> fields;     // the user's fields, in row order
  std::string series;                            // the .pvd file, "" for none
  std::vector<PeriSISSM::SeriesFrame> frames;    // the frames it lists
  std::string current;                           // the file of the frame being written
  PeriSISSM::MeshFrame frame;                    // rank 0: the frame being written
  class MeshView *mesh;
};

}    // namespace LAMMPS_NS

#endif
#endif
