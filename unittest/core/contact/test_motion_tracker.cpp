// Tests of the motion tracker (contact/motion_tracker.h): the largest move of the group's atoms
// since the build and which atom made it; the fraction of a straight move that stays within a
// ball about the build position (on the sphere at that fraction, inside before it); the skin
// thresholds; the reach of a move over a group; without a mask; the reachable inequality of
// pairs chosen between neighbor list builds (sampled), the margin it leaves, explicit runs.

#include "contact/motion_tracker.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace PeriSISSM;
using PeriSISSMContactTest::rows_of;

TEST(MotionTracker, LargestMoveOfTheGroup)
{
  std::vector<std::array<double, 3>> x = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  auto rows = rows_of(x);
  MotionTracker m;
  m.record(rows.data(), 4);
  EXPECT_EQ(m.size(), 4u);
  const int mask[4] = {1, 1, 3, 1};
  int farthest;
  EXPECT_EQ(m.largest_move2(rows.data(), 4, mask, 1, farthest), 0.0);
  EXPECT_EQ(farthest, -1);
  x[1][1] += 0.3;
  x[2][2] += 0.5;    // in group 2 too
  x[3][0] -= 0.4;
  EXPECT_DOUBLE_EQ(m.largest_move2(rows.data(), 4, mask, 1, farthest), 0.25);
  EXPECT_EQ(farthest, 2);
  EXPECT_DOUBLE_EQ(m.largest_move2(rows.data(), 4, mask, 2, farthest), 0.25);
  const int other[4] = {1, 1, 2, 1};
  EXPECT_DOUBLE_EQ(m.largest_move2(rows.data(), 4, other, 1, farthest), 0.16);
  EXPECT_EQ(farthest, 3);
  // a new build forgets the moves
  m.record(rows.data(), 4);
  EXPECT_EQ(m.largest_move2(rows.data(), 4, mask, 1, farthest), 0.0);
}

TEST(MotionTracker, ReachFractionEndsOnTheSphere)
{
  std::mt19937_64 rng(4);
  std::normal_distribution<double> n01;
  std::vector<std::array<double, 3>> build = {{0.3, -0.2, 1.0}};
  auto rows = rows_of(build);
  MotionTracker m;
  m.record(rows.data(), 1);
  const double R = 0.5;
  int cut = 0;
  for (int trial = 0; trial < 200; trial++) {
    double ref[3], end[3], r2 = 0.0;
    for (int d = 0; d < 3; d++) {
      ref[d] = 0.2 * n01(rng);
      end[d] = ref[d] + 0.5 * n01(rng);
      r2 += ref[d] * ref[d];
    }
    if (r2 > R * R) continue;
    for (int d = 0; d < 3; d++) {
      ref[d] += build[0][d];
      end[d] += build[0][d];
    }
    double from;
    const double t = m.reach_fraction(0, ref, end, R, from);
    EXPECT_NEAR(from, std::sqrt(r2), 1e-15);
    auto dist = [&](double s) {
      double e2 = 0.0;
      for (int d = 0; d < 3; d++) {
        const double p = ref[d] + s * (end[d] - ref[d]) - build[0][d];
        e2 += p * p;
      }
      return std::sqrt(e2);
    };
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    if (t == 1.0) {
      EXPECT_LE(dist(1.0), R);
      continue;
    }
    cut++;
    EXPECT_NEAR(dist(t), R, 1e-12);
    EXPECT_LE(dist(t), R);
    for (int k = 0; k <= 20; k++) EXPECT_LE(dist(t * k / 20.0), R * (1.0 + 1e-15));
  }
  EXPECT_GT(cut, 20);
}

TEST(MotionTracker, SkinThresholds)
{
  EXPECT_EQ(MotionTracker::error_distance(0.8), 0.4);
  EXPECT_EQ(MotionTracker::request_distance(0.8), 0.2);
  EXPECT_EQ(MotionTracker::rebuild_distance(0.8), 0.1);
  // predicted: room for 1.5 times the next step's move before skin/2, at most 3/8 skin moved
  EXPECT_FALSE(MotionTracker::rebuild_due(0.19, 0.14, 0.8));    // 0.19 + 0.21 < 0.4
  EXPECT_TRUE(MotionTracker::rebuild_due(0.2, 0.14, 0.8));      // 0.2 + 0.21 > 0.4
  EXPECT_FALSE(MotionTracker::rebuild_due(0.29, 0.0, 0.8));     // a body at rest: 3/8 skin
  EXPECT_TRUE(MotionTracker::rebuild_due(0.31, 0.0, 0.8));
  EXPECT_TRUE(MotionTracker::rebuild_due(0.01, 0.3, 0.8));      // faster than the reach allows
}

// The reach of a move over a group: the smallest fraction, of equals the smallest tag
TEST(MotionTracker, ReachLimitOverTheGroup)
{
  std::vector<std::array<double, 3>> build = {{0, 0, 0}, {5, 0, 0}, {10, 0, 0}, {15, 0, 0}};
  auto rb = rows_of(build);
  MotionTracker m;
  m.record(rb.data(), 4);
  std::vector<std::array<double, 3>> ref = build, end = build;
  end[0][0] += 0.5;    // within R = 1
  end[1][1] += 2.0;    // leaves at t = 0.5
  end[2][2] -= 2.0;    // leaves at t = 0.5 too
  end[3][0] += 4.0;    // leaves at t = 0.25, outside the group
  auto rr = rows_of(ref), re = rows_of(end);
  const int mask[4] = {1, 1, 1, 2};
  const long tag[4] = {4, 9, 7, 1};
  MotionTracker::Reach r = m.reach_limit(rr.data(), re.data(), 4, mask, 1, tag, 1.0);
  EXPECT_NEAR(r.t, 0.5, 1e-12);
  EXPECT_LT(r.t, 0.5);
  EXPECT_EQ(r.atom, 2);    // tag 7 before tag 9
  EXPECT_EQ(r.from, 0.0);
  r = m.reach_limit(rr.data(), re.data(), 4, mask, 3, tag, 1.0);
  EXPECT_EQ(r.atom, 3);
  r = m.reach_limit(rr.data(), re.data(), 1, mask, 1, tag, 1.0);
  EXPECT_EQ(r.t, 1.0);
  EXPECT_EQ(r.atom, -1);
}

// Without a mask every atom counts; moved_at_least2 agrees with largest_move2 on the threshold
// (a move of exactly the limit counts)
TEST(MotionTracker, EveryAtomWithoutMask)
{
  std::vector<std::array<double, 3>> x = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  auto rows = rows_of(x);
  MotionTracker m;
  m.record(rows.data(), 3);
  EXPECT_FALSE(m.moved_at_least2(rows.data(), 3, 1e-300));
  EXPECT_TRUE(m.moved_at_least2(rows.data(), 3, 0.0));
  x[1][2] += 0.5;
  x[2][0] -= 0.75;
  int farthest;
  EXPECT_EQ(m.largest_move2(rows.data(), 3, nullptr, 0, farthest), 0.5625);
  EXPECT_EQ(farthest, 2);
  EXPECT_EQ(m.largest_move2(rows.data(), 2, nullptr, 0, farthest), 0.25);
  EXPECT_EQ(farthest, 1);
  EXPECT_TRUE(m.moved_at_least2(rows.data(), 3, 0.5625));
  EXPECT_FALSE(m.moved_at_least2(rows.data(), 3, 0.5625 * (1.0 + 1e-15)));
  EXPECT_TRUE(m.moved_at_least2(rows.data(), 2, 0.25));
  EXPECT_FALSE(m.moved_at_least2(rows.data(), 2, 0.3));
  // two trackers, recorded at different times, measure from their own positions
  MotionTracker later;
  later.record(rows.data(), 3);
  x[0][1] += 0.1;
  EXPECT_NEAR(later.largest_move2(rows.data(), 3, nullptr, 0, farthest), 0.01, 1e-16);
  EXPECT_EQ(farthest, 0);
  EXPECT_EQ(m.largest_move2(rows.data(), 3, nullptr, 0, farthest), 0.5625);
  m.clear();
  EXPECT_EQ(m.size(), 0u);
}

// The reachable inequality reach + margin + 2 moved <= horizon + skin, checked against pairs:
// two atoms within reach at positions y, each moved by at most `moved` from x_n, are at most
// reach + 2 moved apart at x_n; a pair chosen with margin m at x_c is within reach + m there
// when each moved m/2 from x_c at most. The neighbor list (cutoff horizon + skin at x_n) holds
// every pair that is within reach + m at x_c when reach + m + 2 moved <= horizon + skin.
TEST(MotionTracker, ReachableInequality)
{
  const double reach = 1.35, horizon = 3.0, skin = 2.0;
  EXPECT_EQ(MotionTracker::follow_margin(skin), 0.5);
  // 1.35 + 0.5 + 2 moved <= 5: moved <= 1.575
  EXPECT_TRUE(MotionTracker::reachable(reach, 0.5, 1.575, horizon, skin));
  EXPECT_FALSE(MotionTracker::reachable(reach, 0.5, 1.576, horizon, skin));
  EXPECT_TRUE(MotionTracker::reachable(reach, 0.0, 1.8, horizon, skin));
  EXPECT_FALSE(MotionTracker::reachable(reach, 0.5, NAN, horizon, skin));
  EXPECT_FALSE(MotionTracker::reachable(reach, 0.5, HUGE_VAL, horizon, skin));
  // sampled: pairs within reach + m at x_c (atoms moved by at most `moved` from x_n) are within
  // horizon + skin at x_n whenever reachable() says so
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random_within = [&](double r) {
    std::array<double, 3> d;
    double n2;
    do {
      n2 = 0.0;
      for (int k = 0; k < 3; k++) {
        d[k] = r * u(rng);
        n2 += d[k] * d[k];
      }
    } while (n2 > r * r);
    return d;
  };
  int tried = 0;
  for (int trial = 0; trial < 2000; trial++) {
    const double moved = 2.0 * std::abs(u(rng)), m = 0.5 * std::abs(u(rng));
    if (!MotionTracker::reachable(reach, m, moved, horizon, skin)) continue;
    tried++;
    // at x_c: atoms a and b within reach + m; at x_n each up to `moved` away
    const auto ab = random_within(reach + m), da = random_within(moved), db = random_within(moved);
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) r2 += (ab[k] + db[k] - da[k]) * (ab[k] + db[k] - da[k]);
    EXPECT_LE(std::sqrt(r2), (horizon + skin) * (1.0 + 1e-15));
  }
  EXPECT_GT(tried, 200);
}

// The margin after a move: skin/4 while that is reachable, then what is left of the room, never
// below 0; the margin it gives is reachable at that move
TEST(MotionTracker, ReachableMargin)
{
  const double reach = 1.35, horizon = 3.0, skin = 2.0;
  EXPECT_EQ(MotionTracker::reachable_margin(reach, 0.0, horizon, skin), 0.5);
  EXPECT_EQ(MotionTracker::reachable_margin(reach, 1.5, horizon, skin), 0.5);
  EXPECT_NEAR(MotionTracker::reachable_margin(reach, 1.6, horizon, skin), 0.45, 1e-15);
  EXPECT_NEAR(MotionTracker::reachable_margin(reach, 1.825, horizon, skin), 0.0, 1e-15);
  EXPECT_EQ(MotionTracker::reachable_margin(reach, 3.0, horizon, skin), 0.0);
  for (double moved = 0.0; moved < 1.825; moved += 0.01) {
    const double m = MotionTracker::reachable_margin(reach, moved, horizon, skin);
    EXPECT_GE(m, 0.0);
    EXPECT_LE(m, MotionTracker::follow_margin(skin));
    EXPECT_TRUE(MotionTracker::reachable(reach, m * (1.0 - 1e-12), moved, horizon, skin));
  }
}

// Explicit runs (LAMMPS keeps every move below skin/2): narrow candidates where
// reach + skin/4 <= horizon, the reachable inequality at moved = skin/2
TEST(MotionTracker, Followable)
{
  EXPECT_TRUE(MotionTracker::followable(1.35, 3.0, 2.0));
  EXPECT_TRUE(MotionTracker::followable(2.5, 3.0, 2.0));
  EXPECT_FALSE(MotionTracker::followable(2.6, 3.0, 2.0));
  for (double reach = 0.5; reach < 4.0; reach += 0.25)
    EXPECT_EQ(MotionTracker::followable(reach, 3.0, 2.0),
              MotionTracker::reachable(reach, 0.5, 1.0, 3.0, 2.0));
}

// The errors name the atom, the distances (as %.6g) and the steps
TEST(MotionTracker, ErrorTexts)
{
  EXPECT_EQ(MotionTracker::moved_error(42, 0.0123456789, 300),
            "atom 42 moved 0.0123457 since the last neighbor list build at step 300, more than "
            "half the neighbor skin: contact pairs may be missing; let LAMMPS rebuild the lists "
            "when needed (neigh_modify every 1 delay 0 check yes), use a larger skin or a smaller "
            "time step");
  EXPECT_EQ(MotionTracker::reach_error("fix sissm", 1200, 7, 0.003, 0.00125),
            "fix sissm step 1200 needs atom 7 to move farther than half the neighbor skin "
            "(0.0015) from where it was at the last neighbor list build (it was 0.00125 from "
            "there at the start of the move): the contact candidates cannot follow a step that "
            "far; use a larger neighbor skin (a step may move the atoms by 3/8 of it at least: "
            "the lists are built again after a step that moved an atom skin/8) or a smaller "
            "time step");
}
