// Tests of the short list of short-range contact candidates (peri/contact_candidates.h): for
// each listed atom exactly its neighbors closer than rc, in the list's order, with the list's
// special bits masked off; a list of no atoms; a second choice replaces the first.

#include "peri/contact_candidates.h"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

using PeriSISSM::ContactShortList;

namespace {

constexpr int SPECIAL = 1 << 30;    // a bit the mask removes (LAMMPS's special bits)

// random atoms in a cube, the full list of all pairs within cutoff of the first nlisted atoms
// (every third entry with the special bit), listed in reverse order
struct Cloud {
  std::vector<std::array<double, 3>> pos;
  std::vector<double *> rows;
  std::vector<int> ilist, numneigh;
  std::vector<std::vector<int>> neigh;
  std::vector<int *> firstneigh;

  Cloud(int n, int nlisted, double cutoff, unsigned seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 3.0);
    for (int i = 0; i < n; i++) pos.push_back({u(rng), u(rng), u(rng)});
    for (auto &p : pos) rows.push_back(p.data());
    neigh.resize(n);
    numneigh.assign(n, 0);
    for (int i = nlisted - 1; i >= 0; i--) {
      ilist.push_back(i);
      for (int j = 0; j < n; j++)
        if (j != i && dist2(i, j) < cutoff * cutoff)
          neigh[i].push_back(neigh[i].size() % 3 == 0 ? (j | SPECIAL) : j);
      numneigh[i] = (int) neigh[i].size();
    }
    for (auto &v : neigh) firstneigh.push_back(v.data());
  }
  double dist2(int i, int j) const
  {
    double r2 = 0.0;
    for (int d = 0; d < 3; d++) r2 += (pos[i][d] - pos[j][d]) * (pos[i][d] - pos[j][d]);
    return r2;
  }
  void choose(ContactShortList &s, double rc) const
  {
    s.choose((int) ilist.size(), ilist.data(), numneigh.data(), firstneigh.data(), ~SPECIAL,
             rows.data(), rc);
  }
};

}    // namespace

TEST(ContactShortList, TheNeighborsWithinRangeInListOrder)
{
  const Cloud c(60, 40, 1.2, 3);
  ContactShortList s;
  EXPECT_FALSE(s.chosen());
  for (double rc : {0.3, 0.7, 1.2, 5.0}) {
    c.choose(s, rc);
    ASSERT_TRUE(s.chosen());
    ASSERT_EQ(s.inum, 40);
    ASSERT_EQ(s.first.size(), 41u);
    EXPECT_EQ(s.first[0], 0);
    EXPECT_EQ(s.first[40], (int) s.neigh.size());
    int within = 0;
    for (int ii = 0; ii < s.inum; ii++) {
      const int i = c.ilist[ii];
      std::vector<int> expected;
      for (int j : c.neigh[i]) {
        j &= ~SPECIAL;
        if (c.dist2(i, j) < rc * rc) expected.push_back(j);
      }
      const std::vector<int> got(s.neigh.begin() + s.first[ii], s.neigh.begin() + s.first[ii + 1]);
      EXPECT_EQ(got, expected) << "rc " << rc << " atom " << i;
      within += (int) expected.size();
    }
    EXPECT_EQ(within, (int) s.neigh.size());
    // beyond the list's cutoff: the whole list (masked)
    if (rc > 1.2) {
      int listed = 0;
      for (int i : c.ilist) listed += c.numneigh[i];
      EXPECT_EQ((int) s.neigh.size(), listed);
    }
    if (rc == 0.7) {
      EXPECT_GT(s.neigh.size(), 40u);
    }
  }
  // a closer range afterwards replaces the choice
  c.choose(s, 0.0);
  EXPECT_TRUE(s.neigh.empty());
  EXPECT_EQ(s.first, std::vector<int>(41, 0));
}

TEST(ContactShortList, NoAtoms)
{
  const Cloud c(5, 0, 1.0, 1);
  ContactShortList s;
  c.choose(s, 1.0);
  EXPECT_TRUE(s.chosen());
  EXPECT_EQ(s.inum, 0);
  EXPECT_EQ(s.first, std::vector<int>(1, 0));
  EXPECT_TRUE(s.neigh.empty());
}
