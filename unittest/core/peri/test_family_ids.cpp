// Bookkeeping of bond partners by ID (fix nosb/family after a neighbor list build): new atoms
// take their ID as owntag and a reused ID is reported, renumbered rows are detected, bonds to
// given IDs break once per slot with each row reported once, partners are located (broken ones
// and those not here get -1, the latter listed in row and slot order), and missing bonds break.
#include "family_storage.h"
#include "peri/family_ids.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

using namespace PeriSISSM;

TEST(FamilyIds, NewAtomsAdoptTheirIdAndReusedIdsAreReported)
{
  FamilyStorage<int64_t> s(4);
  s.fill(0, 1, {2});
  s.fill(1, 2, {1});
  // rows 2 and 3: atoms created after the families (owntag 0), IDs 7 (reused) and 11 (new)
  const int64_t tag[4] = {1, 2, 7, 11};
  std::vector<int64_t> reused;
  EXPECT_FALSE(adopt_ids(s.arrays(), 4, tag, int64_t(10), reused));
  EXPECT_EQ(reused, std::vector<int64_t>{7});
  EXPECT_EQ(s.owntag[2], 7);
  EXPECT_EQ(s.owntag[3], 11);

  // a second pass changes nothing
  reused.clear();
  EXPECT_FALSE(adopt_ids(s.arrays(), 4, tag, int64_t(10), reused));
  EXPECT_TRUE(reused.empty());

  // a renumbered atom
  const int64_t renumbered[4] = {1, 3, 7, 11};
  EXPECT_TRUE(adopt_ids(s.arrays(), 4, renumbered, int64_t(10), reused));
  // rows past n are not looked at
  EXPECT_FALSE(adopt_ids(s.arrays(), 1, renumbered, int64_t(10), reused));
}

TEST(FamilyIds, BondsToGivenIdsBreakAndEachRowIsReportedOnce)
{
  FamilyStorage<int> s(3);
  s.fill(0, 1, {2, 5, 9, 5});
  s.fill(1, 2, {1, 3});
  s.fill(2, 3, {0, 9});
  std::vector<int> reshape = {42};
  const std::vector<int> ids = {4, 5, 9};    // sorted
  EXPECT_EQ(break_bonds_to(s.arrays(), 3, ids, reshape), 4);
  EXPECT_EQ(reshape, (std::vector<int>{42, 0, 2}));
  EXPECT_EQ(s.partner[0][0], 2);
  EXPECT_EQ(s.partner[0][1], 0);
  EXPECT_EQ(s.partner[0][2], 0);
  EXPECT_EQ(s.partner[0][3], 0);
  EXPECT_EQ(s.partner[1][0], 1);
  EXPECT_EQ(s.partner[1][1], 3);
  EXPECT_EQ(s.partner[2][1], 0);
  EXPECT_EQ(s.npartner[0], 4);    // slots stay until migration
  reshape.clear();
  EXPECT_EQ(break_bonds_to(s.arrays(), 3, ids, reshape), 0);
  EXPECT_TRUE(reshape.empty());
}

TEST(FamilyIds, PartnersAreLocatedAndMissingOnesListedInOrder)
{
  FamilyStorage<int64_t> s(3);
  const int64_t big = (int64_t(1) << 40) + 5;
  s.fill(0, 1, {2, 0, big, 3});
  s.fill(1, 2, {1, 8});
  s.fill(2, 3, {1});
  // partners here: 1 -> row 0, 2 -> row 1, 3 -> row 2, big -> row 17 (a ghost); 8 is not here
  const std::map<int64_t, int> here = {{1, 0}, {2, 1}, {3, 2}, {big, 17}};
  std::vector<std::pair<int, int>> calls, missing;
  locate_partners(
      s.arrays(), 3,
      [&](int i, int64_t id) {
        calls.emplace_back(i, (int) (id % 1000));
        auto it = here.find(id);
        return it == here.end() ? -1 : 100 * i + it->second;
      },
      missing);
  EXPECT_EQ(s.jlocal[0][0], 1);
  EXPECT_EQ(s.jlocal[0][1], -1);    // broken: not looked up
  EXPECT_EQ(s.jlocal[0][2], 17);
  EXPECT_EQ(s.jlocal[0][3], 2);
  EXPECT_EQ(s.jlocal[1][0], 100);
  EXPECT_EQ(s.jlocal[1][1], -1);
  EXPECT_EQ(s.jlocal[2][0], 200);
  EXPECT_EQ(calls.size(), 6u);    // every unbroken bond once
  EXPECT_EQ(missing, (std::vector<std::pair<int, int>>{{1, 1}}));
  EXPECT_EQ(s.partner[1][1], 8);    // located, not broken

  // two missing slots in one row and one in another: each row reported once
  s.fill(0, 1, {2, 6, 7});
  s.fill(2, 3, {9});
  missing.clear();
  locate_partners(
      s.arrays(), 3,
      [&](int, int64_t id) {
        return id == 2 ? 1 : (id == 1 ? 0 : -1);
      },
      missing);
  EXPECT_EQ(missing, (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 1}, {2, 0}}));
  std::vector<int> reshape;
  break_missing(s.arrays(), missing, reshape);
  EXPECT_EQ(reshape, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(s.partner[0][0], 2);
  EXPECT_EQ(s.partner[0][1], 0);
  EXPECT_EQ(s.partner[0][2], 0);
  EXPECT_EQ(s.partner[1][0], 1);
  EXPECT_EQ(s.partner[1][1], 0);
  EXPECT_EQ(s.partner[2][0], 0);
}
