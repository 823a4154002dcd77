// Tests of the candidates' distances (contact/candidate_distances.h): the first evaluation is
// exact; after a move, a pair far beyond the range carries a lower bound that never exceeds its
// true distance, the pairs within the range and the nearest are exact; new candidates
// (another generation) are evaluated exactly again; the smallest gap.

#include "contact/candidate_distances.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::Scene;

namespace {

Scene scene()
{
  return PeriSISSMContactTest::facing_sheets(0.3, 0.15, 1.6, 1.0 + 1.5 * std::sqrt(2.0), 7);
}

double exact_distance(const Candidate &c, const Scene &s)
{
  Vector3d y[4];
  c.gather(s.rows.data(), y);
  return std::sqrt(c.stencil().distance2(y));
}

}    // namespace

TEST(CandidateDistances, ExactThenBoundedThenExactAgain)
{
  Scene s = scene();
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), 1.0, cands);
  ASSERT_GT(cands.size(), 20u);
  const double range = 0.2, nearest = 1.0;
  CandidateDistances dist;
  EXPECT_FALSE(dist.valid());
  dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest);
  EXPECT_TRUE(dist.valid());
  double smallest = HUGE_VAL;
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    EXPECT_TRUE(dist.exact(ic));
    EXPECT_EQ(dist[ic], exact_distance(cands[ic], s));
    smallest = std::min(smallest, dist[ic] - 0.05);
  }
  EXPECT_EQ(dist.smallest_gap(0.05), smallest);
  EXPECT_EQ(dist.gap_bound(0.05), smallest);

  // a small random move: bounds where they suffice
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n01;
  for (auto &p : s.pos)
    for (int d = 0; d < 3; d++) p[d] += 0.01 * n01(rng);
  dist.invalidate();
  EXPECT_FALSE(dist.valid());
  dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest);
  int bounded = 0;
  double nearest_exact = HUGE_VAL;
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    const double d = exact_distance(cands[ic], s);
    nearest_exact = std::min(nearest_exact, d);
    if (dist.exact(ic)) {
      EXPECT_EQ(dist[ic], d);
    } else {
      bounded++;
      EXPECT_LE(dist[ic], d);
      EXPECT_GE(dist[ic], range);
    }
  }
  EXPECT_GT(bounded, 0);
  // the nearest pair is exact
  double nearest_found = HUGE_VAL;
  for (std::size_t ic = 0; ic < cands.size(); ic++)
    if (dist.exact(ic)) nearest_found = std::min(nearest_found, dist[ic]);
  EXPECT_EQ(nearest_found, nearest_exact);

  // the gap bound is the smallest distance, bounds included
  EXPECT_EQ(dist.gap_bound(0.05), dist.smallest_gap(0.05));
  // set_exact replaces a bound (raises it: the gap bound stays below)
  for (std::size_t ic = 0; ic < cands.size(); ic++)
    if (!dist.exact(ic)) {
      dist.set_exact(ic, exact_distance(cands[ic], s));
      EXPECT_TRUE(dist.exact(ic));
      break;
    }
  EXPECT_LE(dist.gap_bound(0.05), dist.smallest_gap(0.05));

  // another generation: exact again
  dist.evaluate(cands, s.rows.data(), s.n(), 2, range, nearest);
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    EXPECT_TRUE(dist.exact(ic));
    EXPECT_EQ(dist[ic], exact_distance(cands[ic], s));
  }
}
