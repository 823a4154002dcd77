// Tests of the motion tracker (contact/motion_tracker.h): the largest move of the group's atoms
// since the build and which atom made it; the fraction of a straight move that stays within a
// ball about the build position (on the sphere at that fraction, inside before it); the skin
// thresholds; the reach of a move over a group.

#include "contact/motion_tracker.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace PeriSISSM;

namespace {

std::vector<double *> rows_of(std::vector<std::array<double, 3>> &p)
{
  std::vector<double *> r;
  for (auto &q : p) r.push_back(q.data());
  return r;
}

}    // namespace

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
