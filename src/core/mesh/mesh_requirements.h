/* PERI-SISSM core: what read_mesh and fix nosb/mesh require of the deck, and the error messages
   that say what is missing and how to give it. Each function returns "" when all is there.
*/
#ifndef PERISISSM_MESH_MESH_REQUIREMENTS_H
#define PERISISSM_MESH_MESH_REQUIREMENTS_H

#include <string>
#include <vector>

namespace PeriSISSM {

// What the deck has when read_mesh runs.
struct ReadMeshDeck {
  bool box = false;         // the simulation box exists
  bool peri = false;        // atom_style peri: per-atom volume, density, reference position
  bool atom_map = false;    // an atom map (array or hash)
  int dimension = 3;
};

// The message for the first requirement missing, in the order of the members of deck.
std::string read_mesh_unmet(const ReadMeshDeck &deck);

// read_mesh right after read_restart (fixes hold per-atom restart data the new atoms would get
// wrong): the message, advising to re-specify the mesh fix restored_id ("" when the restart
// file holds none).
std::string read_mesh_after_restart(const std::string &restored_id);

// fix ID group nosb/mesh: args (the fix's arguments from ID on), group_all (its group is all),
// ids_and_map (atom IDs and an atom map exist), other (the ID of another fix nosb/mesh of the
// deck, "" if none). The message for the first problem, in that order.
std::string mesh_fix_unmet(const std::vector<std::string> &args, bool group_all, bool ids_and_map,
                           const std::string &other);

}    // namespace PeriSISSM

#endif
