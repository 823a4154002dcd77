/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   read_mesh: one atom_style peri particle per vertex of a triangle mesh file (Wavefront OBJ),
   the triangles kept by fix nosb/mesh (doc/read_mesh.rst).
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(read_mesh,ReadMesh);
// clang-format on
#else

#ifndef LMP_READ_MESH_H
#define LMP_READ_MESH_H

#include "command.h"

namespace LAMMPS_NS {

class ReadMesh : public Command {
 public:
  ReadMesh(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
