// What read_mesh and fix nosb/mesh require of the deck: nothing said when all is there, else the
// first missing requirement with how to give it.
#include "mesh/mesh_requirements.h"

#include <gtest/gtest.h>

#include <string>

using namespace PeriSISSM;

namespace {

bool has(const std::string &message, const std::string &part)
{
  return message.find(part) != std::string::npos;
}

}    // namespace

TEST(MeshRequirements, ReadMeshNamesTheFirstMissingRequirement)
{
  ReadMeshDeck deck;
  deck.box = deck.peri = deck.atom_map = true;
  EXPECT_EQ(read_mesh_unmet(deck), "");
  deck.dimension = 2;
  EXPECT_EQ(read_mesh_unmet(deck), "Read_mesh requires a 3d simulation");
  deck.atom_map = false;
  EXPECT_TRUE(has(read_mesh_unmet(deck), "atom_modify map array (or hash)"));
  deck.peri = false;
  EXPECT_TRUE(has(read_mesh_unmet(deck), "requires atom_style peri"));
  deck.box = false;
  EXPECT_TRUE(has(read_mesh_unmet(deck), "before the simulation box is defined"));
}

TEST(MeshRequirements, AfterRestartAdvisesRunZeroAndTheMeshFix)
{
  const std::string plain = read_mesh_after_restart("");
  EXPECT_TRUE(has(plain, "put 'run 0' before read_mesh (as for create_atoms)"));
  EXPECT_FALSE(has(plain, "re-specify"));
  const std::string with_fix = read_mesh_after_restart("NOSB_MESH");
  EXPECT_EQ(with_fix.find(plain), 0u);
  EXPECT_TRUE(has(with_fix,
                  ", and re-specify 'fix NOSB_MESH all nosb/mesh' right after "
                  "read_restart so that the meshes of the restart file are kept"));
}

TEST(MeshRequirements, MeshFixNamesItsArgumentsGroupMapAndTheOtherFix)
{
  EXPECT_EQ(mesh_fix_unmet({"M", "all", "nosb/mesh"}, true, true, ""), "");
  EXPECT_EQ(mesh_fix_unmet({"M", "all", "nosb/mesh", "yes"}, true, true, ""),
            "Illegal fix nosb/mesh command: no arguments expected, got 'yes'");
  EXPECT_TRUE(has(mesh_fix_unmet({"M", "cloth", "nosb/mesh"}, false, true, ""), "got group cloth"));
  EXPECT_TRUE(has(mesh_fix_unmet({"M", "all", "nosb/mesh"}, true, false, ""),
                  "requires atom IDs and an atom map"));
  EXPECT_EQ(mesh_fix_unmet({"M2", "all", "nosb/mesh"}, true, true, "M"),
            "Fix nosb/mesh M2: fix M of that style exists already; a deck has one (it holds every "
            "mesh)");
  // the arguments are checked first
  EXPECT_TRUE(has(mesh_fix_unmet({"M", "cloth", "nosb/mesh", "x"}, false, false, "N"),
                  "no arguments expected"));
}
