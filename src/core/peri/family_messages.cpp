// The texts of fix nosb/family (see family_messages.h).

#include "peri/family_messages.h"

#include <cstdio>

namespace PeriSISSM {

std::string family_summary(int64_t bonds, int64_t natoms, int64_t singular)
{
  char ratio[64];
  std::snprintf(ratio, sizeof(ratio), "%.8g", natoms ? (double) bonds / natoms : 0.0);
  return "Peridynamic bond families (peri/nosb):\n  total # of bonds = " + std::to_string(bonds) +
      "\n  bonds/atom = " + ratio +
      "\n  atoms with a singular shape tensor = " + std::to_string(singular) + "\n";
}

std::string partner_twice_message(int64_t id, int64_t of)
{
  return "Pair peri/nosb: atom " + std::to_string(id) +
      " appears twice in the bond family of atom " + std::to_string(of) +
      ": the periodic box is shorter than two horizons";
}

std::string same_position_message(int64_t a, int64_t b)
{
  return "Pair peri/nosb: atoms " + std::to_string(a) + " and " + std::to_string(b) +
      " are at the same position";
}

std::string renumbered_message()
{
  return "Pair peri/nosb: atom IDs changed after the bond families were built (bonds are stored "
         "by atom ID): use delete_atoms ... compress no, and do not renumber atoms (reset_atoms "
         "id) once a peri/nosb run has been done";
}

std::string reused_ids_message(int64_t nreused, int64_t nbroken)
{
  return "Pair peri/nosb: " + std::to_string(nreused) +
      " new atoms reuse IDs of deleted atoms; the " + std::to_string(nbroken) +
      " bond ends to those IDs count as broken";
}

std::string lost_partners_message(int64_t nbroken)
{
  return "Pair peri/nosb: " + std::to_string(nbroken) +
      " bond ends lost their partner atom (deleted or lost); those bonds count as broken";
}

}    // namespace PeriSISSM
