/* PERI-SISSM core: the arguments of the read_mesh command.

     read_mesh FILE type T thickness t density rho [offset dx dy dz] [scale s]
               [rotate theta Rx Ry Rz] [group G]

   type, thickness and density are required, each keyword may come in any order (a repeated
   one counts last). Numbers and the atom type are converted by the caller's functions (LAMMPS
   parses them, type labels included), in the order of the arguments. An error is thrown as
   std::invalid_argument with the message "Illegal read_mesh command: ...", naming the keyword
   and the value.
*/
#ifndef PERISISSM_MESH_READ_MESH_OPTIONS_H
#define PERISISSM_MESH_READ_MESH_OPTIONS_H

#include "mesh/mesh_geometry.h"

#include <functional>
#include <string>
#include <vector>

namespace PeriSISSM {

struct ReadMeshOptions {
  std::string file;
  int type = 0;
  double thickness = 0.0;
  double density = 0.0;
  Placement place;
  std::string group;    // empty: none
};

// Inputs: args (the arguments after "read_mesh"); number(what, text) -> a finite number (what
// names the value in its error), type(text) -> an atom type.
// Outputs: the options. Throws std::invalid_argument on a missing, unknown or invalid argument
// (thickness, density and scale must be > 0, the rotate axis nonzero).
ReadMeshOptions
parse_read_mesh(const std::vector<std::string> &args,
                const std::function<double(const char *, const std::string &)> &number,
                const std::function<int(const std::string &)> &type);

}    // namespace PeriSISSM

#endif
