// Tests of the candidates' distances (contact/candidate_distances.h): the first evaluation is
// exact; after a move, a pair far beyond the range carries a lower bound that never exceeds its
// true distance, the pairs within the range and the nearest are exact; new candidates
// (another generation) are evaluated exactly again; the smallest gap; the near and far pairs,
// and the barrier's forces and the path limit from them against those of exact distances.

#include "contact/barrier_potential.h"
#include "contact/candidate_distances.h"
#include "contact/path_limit.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::rows_of;
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
  const double range = 0.2, nearest = 1.0, margin = 0.3;
  CandidateDistances dist;
  EXPECT_FALSE(dist.valid());
  dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest, margin);
  EXPECT_TRUE(dist.valid());
  double smallest = HUGE_VAL;
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    EXPECT_EQ(dist.exact(ic), !dist.far(ic));    // (a far pair's value is a bound once moved)
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
  dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest, margin);
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
    if (!dist.exact(ic) && !dist.far(ic)) {
      dist.set_exact(ic, std::pow(exact_distance(cands[ic], s), 2));
      EXPECT_TRUE(dist.exact(ic));
      break;
    }
  EXPECT_LE(dist.gap_bound(0.05), dist.smallest_gap(0.05));

  // another generation: exact again
  dist.evaluate(cands, s.rows.data(), s.n(), 2, range, nearest, margin);
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    EXPECT_EQ(dist.exact(ic), !dist.far(ic));    // (a far pair's value is a bound once moved)
    EXPECT_EQ(dist[ic], exact_distance(cands[ic], s));
  }
}

namespace {

// the split's rule: near when closer than max(range, smallest capped at nearest) + margin
void expect_split(const CandidateDistances &dist, const std::vector<double> &d, double range,
                  double nearest, double margin)
{
  const double smallest = *std::min_element(d.begin(), d.end());
  const double floor = std::max(range, std::min(smallest, nearest)) + margin;
  std::vector<int> near;
  for (std::size_t ic = 0; ic < d.size(); ic++) {
    EXPECT_EQ(dist.far(ic), d[ic] >= floor) << ic;
    if (d[ic] < floor) near.push_back((int) ic);
  }
  EXPECT_EQ(dist.near(), near);
  EXPECT_EQ(dist.far_bound(), floor);
}

}    // namespace

// The near and far pairs: the split at the first evaluation, the far pairs' bound lowered by
// twice the largest move since (every value a lower bound, the pairs within the range exact)
// while the near list stands, a new split once an atom moved more than half the margin. The
// barrier's forces over the near pairs equal those over exactly evaluated pairs to the bit
// (the same pairs in the same order), and so does the path limit of a move through the gap.
TEST(CandidateDistances, NearPairsAloneUntilAnAtomMovesHalfTheMargin)
{
  Scene s = scene();
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), 1.0, cands);
  for (Candidate &c : cands) {    // (one rank: every point owned, every pair counted)
    for (int k = 0; k < c.nv(); k++) c.own[k] = c.v[k];
    c.counts = true;
  }
  const double range = 0.2, nearest = 1.0, margin = 0.2;
  const auto exact_all = [&] {
    std::vector<double> d;
    for (const Candidate &c : cands) d.push_back(exact_distance(c, s));
    return d;
  };
  CandidateDistances dist;
  dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest, margin);
  std::vector<double> d = exact_all();
  expect_split(dist, d, range, nearest, margin);
  ASSERT_GT(dist.near().size(), 10u);
  ASSERT_LT(dist.near().size() + 10, cands.size());
  EXPECT_EQ(dist.counted(), (long) cands.size());
  const std::vector<int> near = dist.near();
  const std::vector<double> d0 = d;
  const double floor = dist.far_bound();

  // the second sheet towards the first by 0.09 (0.45 of the margin) in two moves
  const BarrierParameters prm{2.0, range - 0.05, 0.05};
  std::vector<double> volume(s.n(), 0.7);
  for (double dz : {0.05, 0.04}) {
    for (int i = 16; i < 32; i++) s.pos[i][2] -= dz;
    dist.invalidate();
    dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest, margin);
    d = exact_all();
    EXPECT_EQ(dist.near(), near);
    int closer = 0;
    for (std::size_t ic = 0; ic < cands.size(); ic++) {
      EXPECT_LE(dist[ic], d[ic] + 1e-15) << ic;    // (a bound as tight as the move: round-off)
      if (d[ic] < range) {
        EXPECT_TRUE(dist.exact(ic));
        EXPECT_EQ(dist[ic], d[ic]);
      }
      if (dist.far(ic) && d[ic] < d0[ic] - 0.01) closer++;
    }
    EXPECT_GT(closer, 0);    // far pairs that came closer than their value at the split
    EXPECT_NEAR(dist.far_bound(), floor - 2.0 * (dz == 0.05 ? 0.05 : 0.09), 1e-14);
    EXPECT_LE(dist.gap_bound(0.05), dist.smallest_gap(0.05));

    // the barrier: bit for bit as from distances all exact (new candidates' first evaluation)
    CandidateDistances fresh;
    fresh.evaluate(cands, s.rows.data(), s.n(), 7, range, nearest, margin);
    std::vector<std::array<double, 3>> fa(s.n(), {0.0, 0.0, 0.0}), fb = fa;
    auto ra = rows_of(fa), rb = rows_of(fb);
    const BarrierTally ta =
        barrier_forces(cands, dist, s.rows.data(), volume.data(), prm, nearest, ra.data());
    const BarrierTally tb =
        barrier_forces(cands, fresh, s.rows.data(), volume.data(), prm, nearest, rb.data());
    EXPECT_GT(ta.nactive[0] + ta.nactive[1], 0);
    for (int k = 0; k < 3; k++) EXPECT_EQ(ta.nactive[k], tb.nactive[k]);
    EXPECT_EQ(ta.mindist, tb.mindist);
    EXPECT_EQ(ta.energy_density, tb.energy_density);
    EXPECT_EQ(fa, fb);

    // a move of the second sheet through the first: the same fraction
    std::vector<std::array<double, 3>> end = s.pos;
    for (int i = 16; i < 32; i++) end[i][2] -= 0.6;
    auto xe = rows_of(end);
    CandidateDistances known = dist;
    const double t = path_limit(cands, s.rows.data(), xe.data(), s.n(), 0.05, nullptr);
    EXPECT_LT(t, 1.0);
    EXPECT_EQ(path_limit(cands, s.rows.data(), xe.data(), s.n(), 0.05, &known), t);
  }

  // another 0.02: 0.11 since the split, more than half the margin: a new split
  for (int i = 16; i < 32; i++) s.pos[i][2] -= 0.02;
  dist.evaluate(cands, s.rows.data(), s.n(), 1, range, nearest, margin);
  d = exact_all();
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    EXPECT_LE(dist[ic], d[ic] + 1e-15) << ic;
    if (d[ic] < range) {
      EXPECT_EQ(dist[ic], d[ic]);
    }
  }
  EXPECT_NE(dist.near(), near);
  EXPECT_GT(dist.far_bound(), range + margin - 1e-15);
  for (std::size_t ic = 0; ic < cands.size(); ic++)
    if (dist.far(ic)) {
      EXPECT_GE(dist[ic], dist.far_bound());
    }
}
