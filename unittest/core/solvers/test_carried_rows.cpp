// Tests of the rows carried across a neighbor list build inside a step (solvers/carried_rows.h):
// atoms spread over two "ranks" are packed, some change ranks, each rank's atoms come back in
// another order, one atom is wrapped by a period; every row comes back to its atom, bit for bit
// (positions of an unwrapped atom, and every other row) or moved by the atom's wrap; an atom
// without a record is reported.

#include "solvers/carried_rows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

using PeriSISSM::CarriedArray;
using PeriSISSM::CarriedRows;

namespace {

// one rank's owned atoms: IDs, positions, a 3-column position array (y), a 2-column array (a)
// and a vector (s); the values of atom ID k are functions of k, so they can be checked anywhere
struct Rank {
  std::vector<std::int64_t> id;
  std::vector<std::array<double, 3>> x, y;
  std::vector<std::array<double, 2>> a;
  std::vector<double> s;
  std::vector<double *> xr, yr, ar;

  void add(std::int64_t k, double wrap)
  {
    id.push_back(k);
    const double base[3] = {0.1 * k + 1.0 / 3.0, -0.01 * k, 1e3 + 0.7 * k};
    x.push_back({base[0] + wrap, base[1], base[2]});
    // y: a position a little away from x (not the same power of two: not exact as x + d)
    y.push_back({base[0] + 1e-3 / 7.0 + wrap, base[1] - 2e-4 / 3.0, base[2] + 1e-5});
    a.push_back({1.0 / (k + 1.0), -3.0 * k});
    s.push_back(k * k + 0.5);
  }
  std::vector<CarriedArray> arrays()
  {
    xr.clear();
    yr.clear();
    ar.clear();
    for (auto &p : x) xr.push_back(p.data());
    for (auto &p : y) yr.push_back(p.data());
    for (auto &p : a) ar.push_back(p.data());
    CarriedArray cy, ca, cs;
    cy.rows = yr.data();
    cy.cols = 3;
    cy.position = true;
    ca.rows = ar.data();
    ca.cols = 2;
    cs.vector = s.data();
    return {cy, ca, cs};
  }
};

}    // namespace

TEST(CarriedRows, RowsFollowTheirAtomsAcrossRanks)
{
  const double period = 2.5;
  Rank before[2];
  for (int k = 1; k <= 20; k++) before[k % 2].add(k, 0.0);
  CarriedRows carry[2] = {CarriedRows(before[0].arrays()), CarriedRows(before[1].arrays())};
  for (int r = 0; r < 2; r++) {
    EXPECT_EQ(carry[r].width(), 1 + 3 + 3 + 2 + 1);
    carry[r].pack((int) before[r].id.size(), before[r].id.data(), before[r].xr.data());
  }

  // after: IDs 3, 4 and 17 changed ranks, every rank's order is shuffled, ID 8 is wrapped by
  // -period in x (its position and its position rows move with it)
  std::set<std::int64_t> owned[2];
  for (int k = 1; k <= 20; k++) owned[k % 2].insert(k);
  for (std::int64_t k : {3, 4, 17}) {
    owned[k % 2].erase(k);
    owned[1 - k % 2].insert(k);
  }
  std::vector<double> sent[2];
  for (int r = 0; r < 2; r++)
    sent[r] = carry[r].departed([&](std::int64_t k) {
      return owned[r].count(k) > 0;
    });
  EXPECT_EQ(sent[0].size(), 1u * carry[0].width());    // ID 4
  EXPECT_EQ(sent[1].size(), 2u * carry[1].width());    // IDs 3 and 17

  std::mt19937 rng(7);
  for (int r = 0; r < 2; r++) {
    std::vector<std::int64_t> ids(owned[r].begin(), owned[r].end());
    std::shuffle(ids.begin(), ids.end(), rng);
    Rank after;
    for (std::int64_t k : ids) after.add(k, k == 8 ? -period : 0.0);
    // the arrays hold garbage before the unpack
    for (auto &p : after.y) p = {-1.0, -1.0, -1.0};
    for (auto &p : after.a) p = {-1.0, -1.0};
    for (double &v : after.s) v = -1.0;
    carry[r].set_arrays(after.arrays());
    EXPECT_EQ(carry[r].unpack((int) ids.size(), after.id.data(), after.xr.data(), sent[1 - r]), -1);

    Rank expect;
    for (std::int64_t k : ids) expect.add(k, 0.0);
    for (std::size_t i = 0; i < ids.size(); i++) {
      for (int c = 0; c < 3; c++) {
        if (ids[i] == 8 && c == 0) {
          EXPECT_NEAR(after.y[i][c], expect.y[i][c] - period, 1e-15);
        } else {
          EXPECT_EQ(after.y[i][c], expect.y[i][c]) << ids[i];
        }
      }
      EXPECT_EQ(after.a[i], expect.a[i]) << ids[i];
      EXPECT_EQ(after.s[i], expect.s[i]) << ids[i];
    }
  }
}

TEST(CarriedRows, AnAtomWithoutRecordIsReported)
{
  Rank r;
  for (int k = 1; k <= 3; k++) r.add(k, 0.0);
  CarriedRows carry(r.arrays());
  carry.pack(3, r.id.data(), r.xr.data());
  // ID 9 arrives with nothing sent for it: the first such atom is named, the others written
  Rank after;
  for (std::int64_t k : {2, 9, 1}) after.add(k, 0.0);
  after.s = {-1.0, -1.0, -1.0};
  carry.set_arrays(after.arrays());
  EXPECT_EQ(carry.unpack(3, after.id.data(), after.xr.data(), {}), 1);
  EXPECT_EQ(after.s[0], 4.5);
  EXPECT_EQ(after.s[1], -1.0);
  EXPECT_EQ(after.s[2], 1.5);
  // no atoms: nothing packed, nothing departs
  CarriedRows none(r.arrays());
  none.pack(0, nullptr, nullptr);
  EXPECT_TRUE(none.departed([](std::int64_t) {
                    return false;
                  })
                  .empty());
  EXPECT_EQ(none.unpack(0, nullptr, nullptr, {}), -1);
}
