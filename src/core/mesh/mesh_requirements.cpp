/* PERI-SISSM core: what read_mesh and fix nosb/mesh require (see mesh_requirements.h). */
#include "mesh/mesh_requirements.h"

namespace PeriSISSM {

std::string read_mesh_unmet(const ReadMeshDeck &deck)
{
  if (!deck.box)
    return "Read_mesh command before the simulation box is defined: create the box first "
           "(region and create_box)";
  if (!deck.peri)
    return "Read_mesh requires atom_style peri (per-atom volume, density and reference "
           "position): write atom_style peri before the box is created";
  if (!deck.atom_map)
    return "Read_mesh requires an atom map (triangles are stored by atom ID): write atom_modify "
           "map array (or hash) before the box is created";
  if (deck.dimension != 3) return "Read_mesh requires a 3d simulation";
  return "";
}

std::string read_mesh_after_restart(const std::string &restored_id)
{
  std::string message = "Read_mesh after read_restart: the restart file holds per-atom data of "
                        "fixes, which they take from it when defined or at the first run; put "
                        "'run 0' before read_mesh (as for create_atoms)";
  if (!restored_id.empty())
    message += ", and re-specify 'fix " + restored_id +
        " all nosb/mesh' right after read_restart so that the meshes of the restart file are kept";
  return message;
}

std::string mesh_fix_unmet(const std::vector<std::string> &args, bool group_all, bool ids_and_map,
                           const std::string &other)
{
  if (args.size() != 3)
    return "Illegal fix nosb/mesh command: no arguments expected, got '" +
        (args.size() > 3 ? args[3] : std::string()) + "'";
  if (!group_all)
    return "Fix nosb/mesh must be defined for group all (it holds every mesh of the deck), got "
           "group " +
        args[1];
  if (!ids_and_map)
    return "Fix nosb/mesh requires atom IDs and an atom map: use atom_modify map array (or hash) "
           "before the box is created";
  if (!other.empty())
    return "Fix nosb/mesh " + args[0] + ": fix " + other +
        " of that style exists already; a deck has one (it holds every mesh)";
  return "";
}

}    // namespace PeriSISSM
