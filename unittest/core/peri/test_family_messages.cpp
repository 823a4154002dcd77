// The texts of fix nosb/family (peri/family_messages.h): the numbers in their places, 64-bit
// IDs and counts in full, the bonds per atom to 8 digits and 0 without atoms.
#include "peri/family_messages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

using namespace PeriSISSM;

TEST(FamilyMessages, SummaryOfABuild)
{
  EXPECT_EQ(family_summary(10, 4, 1),
            "Peridynamic bond families (peri/nosb):\n  total # of bonds = 10\n"
            "  bonds/atom = 2.5\n  atoms with a singular shape tensor = 1\n");
  const int64_t big = int64_t(1) << 40;
  EXPECT_EQ(family_summary(big, 3, 0),
            "Peridynamic bond families (peri/nosb):\n  total # of bonds = 1099511627776\n"
            "  bonds/atom = 3.6650388e+11\n  atoms with a singular shape tensor = 0\n");
  EXPECT_NE(family_summary(0, 0, 0).find("  bonds/atom = 0\n"), std::string::npos);
}

TEST(FamilyMessages, ErrorsAndWarningsNameTheirAtomsAndCounts)
{
  const int64_t big = int64_t(1) << 40;
  EXPECT_EQ(partner_twice_message(big, 7),
            "Pair peri/nosb: atom 1099511627776 appears twice in the bond family of atom 7: the "
            "periodic box is shorter than two horizons");
  EXPECT_EQ(same_position_message(3, 12),
            "Pair peri/nosb: atoms 3 and 12 are at the same position");
  EXPECT_EQ(reused_ids_message(2, 17),
            "Pair peri/nosb: 2 new atoms reuse IDs of deleted atoms; the 17 bond ends to those "
            "IDs count as broken");
  EXPECT_EQ(lost_partners_message(5),
            "Pair peri/nosb: 5 bond ends lost their partner atom (deleted or lost); those bonds "
            "count as broken");
  const std::string renumbered = renumbered_message();
  EXPECT_EQ(renumbered.find("Pair peri/nosb: atom IDs changed"), 0u);
  EXPECT_NE(renumbered.find("delete_atoms ... compress no"), std::string::npos);
  EXPECT_NE(renumbered.find("reset_atoms id"), std::string::npos);
}
