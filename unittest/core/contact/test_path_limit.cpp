// Tests of the path limit (contact/path_limit.h): with one pair it is that pair's CCD fraction;
// over many pairs the smallest; the skip by known gaps gives the same fraction as the CCD of
// every pair; no move, no limit; the scaled move keeps every pair apart (sampled); a move
// shorter than the gaps allow gives 1 without looking at a pair; an earlier end t_max gives
// min(t, t_max); scale_move() moves the group's atoms only.

#include "contact/path_limit.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::rows_of;
using PeriSISSMContactTest::Scene;

TEST(PathLimit, OnePairIsItsCcd)
{
  std::vector<std::array<double, 3>> a = {{0, 0, 0}, {1, 0, 0}}, b = {{0.5, 0, 0}, {0.5, 0, 0}};
  auto ra = rows_of(a), rb = rows_of(b);
  Candidate c{StencilType::kPointPoint, {1, 2, 0, 0}, {0, 1, -1, -1}};
  const std::vector<Candidate> cands = {c};
  CcdOptions opt;
  opt.dmin = 0.1;
  const double t = path_limit(cands, ra.data(), rb.data(), (int) ra.size(), 0.1, nullptr);
  EXPECT_EQ(t,
            point_point_ccd(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0, 0),
                            Vector3d(-0.5, 0, 0), opt));
  EXPECT_LT(t, 0.9);
  // no move: no limit
  EXPECT_EQ(path_limit(cands, ra.data(), ra.data(), (int) ra.size(), 0.1, nullptr), 1.0);
}

TEST(PathLimit, SheetsPressedTogether)
{
  Scene s = PeriSISSMContactTest::facing_sheets(0.3, 0.15, 0.5, 1.0 + 1.5 * std::sqrt(2.0), 9);
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), 1.0, cands);
  // the move: the second sheet down by 0.5 with some noise, the first particle sideways
  std::vector<std::array<double, 3>> end = s.pos;
  std::mt19937_64 rng(2);
  std::normal_distribution<double> n01;
  for (int i = 16; i < 32; i++) {
    end[i][2] -= 0.5;
    for (int d = 0; d < 3; d++) end[i][d] += 0.01 * n01(rng);
  }
  end[32][0] += 0.3;
  auto xe = rows_of(end);
  const double dmin = 0.02;
  const double t = path_limit(cands, s.rows.data(), xe.data(), s.n(), dmin, nullptr);
  // the smallest of the pairs' CCD fractions
  double smallest = 1.0;
  CcdOptions opt;
  opt.dmin = dmin;
  for (const Candidate &c : cands) {
    Vector3d y[4], dy[4];
    for (int k = 0; k < c.nv(); k++)
      for (int d = 0; d < 3; d++) {
        y[k][d] = s.pos[c.v[k]][d];
        dy[k][d] = end[c.v[k]][d] - s.pos[c.v[k]][d];
      }
    smallest = std::min(smallest, c.stencil().ccd(y, dy, opt));
  }
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 0.6);
  EXPECT_LE(t, smallest);
  EXPECT_GE(t, 0.5 * smallest);
  // the known gaps at the start skip pairs but give the same fraction
  CandidateDistances known;
  known.evaluate(cands, s.rows.data(), s.n(), 1, 0.2, 1.0, 0.3);
  EXPECT_EQ(path_limit(cands, s.rows.data(), xe.data(), s.n(), dmin, &known), t);
  // an end before 1 (the caller's reach) gives the smaller of the two, with and without gaps
  for (double t_max : {2.0 * t, 1.0001 * t, t, 0.5 * t, 0.0}) {
    EXPECT_EQ(path_limit(cands, s.rows.data(), xe.data(), s.n(), dmin, nullptr, t_max),
              std::min(t, t_max));
    EXPECT_EQ(path_limit(cands, s.rows.data(), xe.data(), s.n(), dmin, &known, t_max),
              std::min(t, t_max));
  }
  // every pair stays beyond dmin along the scaled move
  for (int k = 0; k <= 100; k++) {
    const double tau = t * k / 100.0;
    std::vector<std::array<double, 3>> mid = s.pos;
    for (int i = 0; i < s.n(); i++)
      for (int d = 0; d < 3; d++) mid[i][d] += tau * (end[i][d] - s.pos[i][d]);
    auto rm = rows_of(mid);
    for (const Candidate &c : cands) {
      Vector3d y[4];
      c.gather(rm.data(), y);
      EXPECT_GT(std::sqrt(c.stencil().distance2(y)), dmin);
    }
  }
}

// A move shorter than the gaps allow: move_within_gaps() says so exactly when twice the longest
// move is within 0.9 of the smallest gap, and path_limit() then returns 1 and leaves the known
// distances as they were (those not exact stay bounds)
TEST(PathLimit, MoveWithinGapsSkipsThePairs)
{
  Scene s = PeriSISSMContactTest::facing_sheets(0.3, 0.15, 0.5, 1.0 + 1.5 * std::sqrt(2.0), 9);
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), 1.0, cands);
  ASSERT_GT(cands.size(), 10u);
  const double dmin = 0.02;
  CandidateDistances known;
  EXPECT_FALSE(move_within_gaps(s.rows.data(), s.rows.data(), s.n(), dmin, known));    // unknown
  known.evaluate(cands, s.rows.data(), s.n(), 1, 0.2, 1.0, 0.3);
  const double gap = known.smallest_gap(dmin);
  ASSERT_GT(gap, 0.0);
  EXPECT_TRUE(move_within_gaps(s.rows.data(), s.rows.data(), s.n(), dmin, known));    // no move
  // the second sheet straight towards the first (the closing move), the rest at random
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double f : {0.449, 0.451}) {
    const double l = f * gap;
    std::vector<std::array<double, 3>> end = s.pos;
    for (int i = 0; i < s.n(); i++) {
      if (i >= 16 && i < 32) {
        end[i][2] -= l;
        continue;
      }
      Vector3d d(u(rng), u(rng), u(rng));
      d *= l / d.norm();
      for (int k = 0; k < 3; k++) end[i][k] += d[k];
    }
    auto xe = rows_of(end);
    const bool within = move_within_gaps(s.rows.data(), xe.data(), s.n(), dmin, known);
    EXPECT_EQ(within, 2.0 * f <= 0.9) << f;
    if (!within) continue;
    CandidateDistances after = known;
    EXPECT_EQ(path_limit(cands, s.rows.data(), xe.data(), s.n(), dmin, &after), 1.0);
    for (std::size_t ic = 0; ic < cands.size(); ic++) {
      EXPECT_EQ(after[ic], known[ic]);
      EXPECT_EQ(after.exact(ic), known.exact(ic));
    }
  }
}

// The move cut to a fraction: the group's atoms at xref + t (x - xref), the others left at x
TEST(PathLimit, ScaleMove)
{
  std::vector<std::array<double, 3>> ref = {{0, 0, 0}, {1, 1, 1}, {2, -1, 0.5}};
  std::vector<std::array<double, 3>> x = {{1, 2, -4}, {3, 1, 0}, {5, 5, 5}};
  const std::vector<std::array<double, 3>> end = x;
  auto rr = rows_of(ref), rx = rows_of(x);
  const int mask[3] = {3, 1, 2};
  scale_move(rr.data(), rx.data(), 3, mask, 1, 0.25);
  for (int d = 0; d < 3; d++) {
    EXPECT_EQ(x[0][d], ref[0][d] + 0.25 * (end[0][d] - ref[0][d]));
    EXPECT_EQ(x[1][d], ref[1][d] + 0.25 * (end[1][d] - ref[1][d]));
    EXPECT_EQ(x[2][d], end[2][d]);
  }
  EXPECT_EQ(x[0][1], 0.5);
  EXPECT_EQ(x[1][0], 1.5);
  // t = 0: back at the reference; t = 1: unchanged
  scale_move(rr.data(), rx.data(), 3, mask, 2, 0.0);
  EXPECT_EQ(x[2], ref[2]);
  EXPECT_EQ(x[0], ref[0]);
  const auto before = x;
  scale_move(rr.data(), rx.data(), 3, mask, 1, 1.0);
  EXPECT_EQ(x, before);
}
