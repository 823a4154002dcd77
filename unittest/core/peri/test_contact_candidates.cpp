// Tests of the short list of short-range contact candidates (peri/contact_candidates.h): for
// each listed atom exactly its neighbors closer than rc, in the list's order, with the list's
// special bits masked off; a list of no atoms; a second choice replaces the first. The follower:
// the margin at a build (the skin, or skin/4 when followed, with the positions kept), when the
// pairs are chosen again as atoms move, and the error text of a step that moved too far.

#include "peri/contact_candidates.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using PeriSISSM::ContactFollower;
using PeriSISSM::ContactShortList;
using PeriSISSM::MotionTracker;

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
  void choose(ContactFollower &f, double margin) const
  {
    f.choose((int) ilist.size(), ilist.data(), numneigh.data(), firstneigh.data(), ~SPECIAL,
             rows.data(), (int) pos.size(), margin, 5);
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
    if (rc == 0.7) { EXPECT_GT(s.neigh.size(), 40u); }
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

TEST(ContactFollower, MarginAtBuildAndPositionsKept)
{
  Cloud c(30, 30, 1.5, 7);
  const double skin = 0.4;
  ContactFollower f;
  f.reach = 0.5;
  f.horizon = 0.55;    // reach + skin/4 > horizon: an explicit run does not follow
  EXPECT_EQ(f.margin_at_build(c.rows.data(), 30, skin), skin);
  EXPECT_FALSE(f.followed());
  EXPECT_FALSE(f.current(-1));    // never chosen
  EXPECT_EQ(f.at_build.size(), 0u);
  c.choose(f, skin);
  const PeriSISSM::ContactCandidates cand = f.candidates(c.ilist.data());
  EXPECT_EQ(cand.inum, 30);
  EXPECT_EQ(cand.ilist, c.ilist.data());
  EXPECT_EQ(cand.first, f.list.first.data());
  EXPECT_EQ(cand.neigh, f.list.neigh.data());
  EXPECT_TRUE(f.current(5));
  EXPECT_FALSE(f.current(6));
  EXPECT_EQ(f.bytes(), (double) (f.list.first.capacity() + f.list.neigh.capacity()) * sizeof(int));
  EXPECT_EQ(f.margin(), skin);
  EXPECT_EQ(f.at_choice.size(), 0u);
  ContactShortList expected;
  c.choose(expected, f.reach + skin);
  EXPECT_EQ(f.list.neigh, expected.neigh);

  f.horizon = 0.65;    // reach + skin/4 <= horizon: followed
  EXPECT_EQ(f.margin_at_build(c.rows.data(), 30, skin), MotionTracker::follow_margin(skin));
  EXPECT_TRUE(f.followed_explicit());
  EXPECT_EQ(f.at_build.size(), 30u);
  c.choose(f, 0.1);
  EXPECT_EQ(f.at_choice.size(), 30u);
  EXPECT_GE(f.bytes(), 2.0 * 3 * 30 * sizeof(double));

  f.track(true);    // an implicit integrator: followed, not as an explicit run
  EXPECT_FALSE(f.followed_explicit());
  f.horizon = 0.55;
  EXPECT_EQ(f.margin_at_build(c.rows.data(), 30, skin), MotionTracker::follow_margin(skin));
  EXPECT_TRUE(f.tracked() && f.followed() && !f.followed_explicit());
  f.track(false);    // positions forgotten
  EXPECT_EQ(f.at_build.size(), 0u);
  EXPECT_EQ(f.at_choice.size(), 0u);
}

TEST(ContactFollower, ChosenAgainAfterHalfTheMargin)
{
  Cloud c(30, 30, 1.5, 11);
  const double skin = 0.4, margin = MotionTracker::follow_margin(skin);
  ContactFollower f;
  f.reach = 0.5;
  f.horizon = 0.65;
  f.margin_at_build(c.rows.data(), 30, skin);
  c.choose(f, margin);
  double m = -1.0;
  c.pos[4][0] += 0.49 * margin;    // below half the margin: complete
  EXPECT_FALSE(f.explicit_rechoice(c.rows.data(), 30, skin, m));
  EXPECT_EQ(m, -1.0);
  c.pos[4][0] += 0.02 * margin;
  ASSERT_TRUE(f.explicit_rechoice(c.rows.data(), 30, skin, m));
  EXPECT_EQ(m, MotionTracker::reachable_margin(f.reach, 0.51 * margin, f.horizon, skin));

  double moves2[2];
  int farthest;
  c.pos[9][1] -= 0.3 * margin;
  f.local_moves2(c.rows.data(), 30, moves2, farthest);
  EXPECT_EQ(farthest, 4);
  EXPECT_NEAR(std::sqrt(moves2[0]), 0.51 * margin, 1e-12);
  EXPECT_NEAR(std::sqrt(moves2[1]), 0.51 * margin, 1e-12);
  f.track(true);    // not an explicit run: never chosen again by explicit_rechoice()
  f.margin_at_build(c.rows.data(), 30, skin);
  EXPECT_FALSE(f.explicit_rechoice(c.rows.data(), 30, skin, m));
  c.pos[4][0] += 0.51 * margin;
  c.choose(f, margin);    // a new choice: moves from it start at zero, from the build stay
  f.local_moves2(c.rows.data(), 30, moves2, farthest);
  EXPECT_EQ(moves2[0], 0.0);
  EXPECT_NEAR(std::sqrt(moves2[1]), 0.51 * margin, 1e-12);
  f.local_moves2(c.rows.data(), 4, moves2, farthest);    // owned atoms only: atom 4 is not
  EXPECT_EQ(farthest, -1);
}

TEST(ContactFollower, ImplicitIteratesAndTheStepLimit)
{
  ContactFollower f;
  f.reach = 0.5;
  f.horizon = 0.6;
  const double skin = 0.4;
  double x[1][3] = {{0.0, 0.0, 0.0}};
  double *rows[1] = {x[0]};
  f.track(true);
  f.margin_at_build(rows, 1, skin);
  const int ilist[1] = {0}, numneigh[1] = {0};
  int *firstneigh[1] = {nullptr};
  f.choose(1, ilist, numneigh, firstneigh, ~0, rows, 1, 0.1, 7);
  // reachable while reach + skin/4 + 2 moved <= horizon + skin: moved <= 0.2
  EXPECT_TRUE(f.reachable(0.19, skin));
  EXPECT_FALSE(f.reachable(0.21, skin));
  EXPECT_FALSE(f.reachable(NAN, skin));
  EXPECT_EQ(f.after_motion(0.049, 0.1, skin), 0);
  EXPECT_EQ(f.after_motion(0.05, 0.1, skin), 1);
  EXPECT_EQ(f.after_motion(0.0, 0.25, skin), -1);
  // a (sub-)step starts from a new list beyond skin/4 = 0.1, cannot start beyond 0.2
  EXPECT_EQ(f.build_wanted(0.0, skin), 0);
  EXPECT_EQ(f.build_wanted(0.1, skin), 0);
  EXPECT_EQ(f.build_wanted(0.1001, skin), 1);
  EXPECT_EQ(f.build_wanted(0.2, skin), 1);
  EXPECT_EQ(f.build_wanted(0.2001, skin), 2);
  EXPECT_EQ(f.build_wanted(NAN, skin), 2);
  const std::string e = f.too_far(12, 345, 0.25, skin, "");
  EXPECT_EQ(e.rfind("Pair peri/nosb: the implicit step 12 moved atom 345 by 0.25 from", 0), 0u)
      << e;
  EXPECT_NE(e.find("with neighbor skin 0.4 (a step may"), std::string::npos) << e;
  EXPECT_NE(e.find("/ 4 = 0.15); use a smaller"), std::string::npos) << e;
  EXPECT_NE(e.find("skin of at least 0.8, or turn"), std::string::npos) << e;
  EXPECT_NE(f.too_far(12, 345, 0.25, skin, "why").find("= 0.15); why; use"), std::string::npos);
}
