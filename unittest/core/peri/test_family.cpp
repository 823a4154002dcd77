// Order of a bond family (by partner ID, whatever order the neighbor list gave) with the
// duplicate a too short periodic box makes, and the damage of a particle from its broken bonds.
#include "peri/family.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

using namespace PeriSISSM;

TEST(FamilyOrder, PartnersAreSortedByIdWhateverTheListOrder)
{
  std::vector<std::pair<int64_t, int>> a = {{7, 3}, {2, 9}, {(int64_t(1) << 40), 0}, {5, 1}};
  std::vector<std::pair<int64_t, int>> b = {a[2], a[0], a[3], a[1]};
  EXPECT_EQ(order_family(a), 0);
  EXPECT_EQ(order_family(b), 0);
  EXPECT_EQ(a, b);
  const std::vector<std::pair<int64_t, int>> expected = {
      {2, 9}, {5, 1}, {7, 3}, {(int64_t(1) << 40), 0}};
  EXPECT_EQ(a, expected);

  std::vector<std::pair<int, int>> none;
  EXPECT_EQ(order_family(none), 0);
}

TEST(FamilyOrder, TwoImagesOfOneParticleAreReportedBySmallestId)
{
  // particles 8 and 4 both appear twice (two periodic images: different local indices)
  std::vector<std::pair<int, int>> f = {{8, 12}, {4, 2}, {8, 3}, {6, 5}, {4, 20}};
  EXPECT_EQ(order_family(f), 4);
  EXPECT_EQ(f[0], std::make_pair(4, 2));    // images by local index
  EXPECT_EQ(f[1], std::make_pair(4, 20));
}

TEST(FamilyDamage, BrokenBondsCountByTheirWeight)
{
  const int partner[4] = {3, 0, 9, 0};
  const double omega[4] = {1.0, 2.0, 0.5, 0.5};
  EXPECT_EQ(damage(4, partner, omega, 4.0), 1.0 - 1.5 / 4.0);
  const int intact[4] = {3, 4, 9, 10};
  EXPECT_EQ(damage(4, intact, omega, 4.0), 0.0);
  const int broken[4] = {0, 0, 0, 0};
  EXPECT_EQ(damage(4, broken, omega, 4.0), 1.0);
  // no initial family (a particle created later): no damage
  EXPECT_EQ(damage(0, partner, omega, 0.0), 0.0);
}
