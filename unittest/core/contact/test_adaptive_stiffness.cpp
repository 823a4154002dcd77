// Tests of kappa's rule (contact/adaptive_stiffness.h): the bounds from the scene are those of
// initial_barrier_stiffness() (kappa_max = 100 kappa_min) and the stiffness starts at the lower
// one; a restart clamps to them; the doubling only while the smallest gap is tiny and
// shrinking, capped; the balance minimises |grad E + kappa grad B| inside the bounds; the sums
// of the balance against a direct computation over the owned atoms of the group; the scene's
// extent (bounding box diagonal, mean mass) reduced over parts as over the whole.

#include "contact/adaptive_stiffness.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::Scene;

TEST(AdaptiveStiffness, BoundsFromTheScene)
{
  AdaptiveStiffness k;
  EXPECT_FALSE(k.measured());
  k.set_scene(2.0, 0.5, 1e-3);
  EXPECT_TRUE(k.measured());
  double kmax;
  const double kmin = initial_barrier_stiffness(2.0, 1e-3, 0.5, 0.0, 0.0, kmax);
  EXPECT_EQ(k.lower(), kmin);
  EXPECT_EQ(k.upper(), kmax);
  EXPECT_DOUBLE_EQ(k.upper(), 100.0 * k.lower());
  EXPECT_EQ(k.value(), kmin);
  EXPECT_EQ(k.bbox_diagonal(), 2.0);
  EXPECT_EQ(k.mean_mass(), 0.5);
  k.restore(10.0 * kmax);
  EXPECT_EQ(k.value(), kmax);
  k.restore(0.1 * kmin);
  EXPECT_EQ(k.value(), kmin);
  k.restore(3.0 * kmin);
  EXPECT_EQ(k.value(), 3.0 * kmin);
}

TEST(AdaptiveStiffness, DoublesWhileTheGapIsTinyAndShrinking)
{
  AdaptiveStiffness k;
  k.set_scene(1.0, 1.0, 1e-3);
  const double k0 = k.value();
  k.begin_step();
  // the first iterate of a step: no previous gap to shrink from
  EXPECT_EQ(k.at_iterate(1e-10), k0);
  // shrinking below 1e-9 of the diagonal: doubled
  const double k1 = k.at_iterate(5e-11);
  EXPECT_EQ(k1, std::min(2.0 * k0, k.upper()));
  k.set(k1);
  // growing: the same
  EXPECT_EQ(k.at_iterate(8e-11), k1);
  // large gaps: the same
  k.begin_step();
  EXPECT_EQ(k.at_iterate(1e-3), k1);
  EXPECT_EQ(k.at_iterate(1e-4), k1);
  // capped at the upper bound
  k.set(k.upper());
  k.begin_step();
  k.at_iterate(1e-10);
  EXPECT_EQ(k.at_iterate(1e-11), k.upper());
}

TEST(AdaptiveStiffness, BalanceMinimisesTheResidualInsideTheBounds)
{
  AdaptiveStiffness k;
  k.set_scene(1.0, 1.0, 1e-3);
  k.set(2.0 * k.lower());
  // grad E = -res_dot_grad/|gB|... : with |grad B|^2 = 4 and res V . grad B = r, grad E . grad B
  // = -r - kappa_ip 4, the minimiser is (r + 4 kappa_ip) / 4 = kappa_ip + r / 4
  const double kip = k.value();
  EXPECT_DOUBLE_EQ(k.balanced(4.0 * kip, 4.0), 2.0 * kip);
  EXPECT_EQ(k.balanced(-100.0 * kip, 4.0), k.lower());
  EXPECT_EQ(k.balanced(1e6 * kip, 4.0), k.upper());
}

TEST(AdaptiveStiffness, BalanceSumsOverTheGroup)
{
  Scene s;
  s.add(0.0, 0.0, 0.0, ContactRole::kParticle);
  s.add(0.05, 0.0, 0.0, ContactRole::kParticle);
  s.add(0.0, 0.08, 0.0, ContactRole::kParticle);
  s.add(3.0, 0.0, 0.0, ContactRole::kParticle);
  s.finish(1.0, 1);
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), 0.5, cands);
  ASSERT_EQ(cands.size(), 3u);
  for (Candidate &c : cands)
    for (int k = 0; k < 2; k++) c.own[k] = c.v[k];
  const double dhat = 0.1, dmin = 0.01;
  CandidateDistances dist;
  std::vector<std::array<double, 3>> res = {{1, 2, 3}, {-1, 0.5, 2}, {0.3, 0.1, -0.2}, {1, 1, 1}};
  std::vector<double *> rres;
  for (auto &r : res) rres.push_back(r.data());
  const double volume[4] = {0.5, 2.0, 1.0, 1.0};
  const int mask[4] = {1, 1, 0, 1};
  // distances not valid: nothing active
  BalanceSums b =
      balance_sums(cands, dist, s.rows.data(), rres.data(), volume, mask, 1, 4, dhat, dmin);
  EXPECT_FALSE(b.active);
  dist.evaluate(cands, s.rows.data(), s.n(), 1, dmin + dhat, 1.0, 0.1);
  b = balance_sums(cands, dist, s.rows.data(), rres.data(), volume, mask, 1, 4, dhat, dmin);
  EXPECT_TRUE(b.active);
  // direct: the three pairs among atoms 0, 1, 2 (0-1 at 0.05, 0-2 at 0.08 are active; 1-2 at
  // 0.094 is active too), atom 2 outside the group
  const BarrierParameters unit{1.0, dhat, dmin};
  std::vector<Vector3d> grad(4, Vector3d::Zero());
  for (const Candidate &c : cands) {
    Vector3d y[2];
    c.gather(s.rows.data(), y);
    const Vector6d g = point_point_barrier_gradient(y[0], y[1], unit);
    grad[c.v[0]] += g.head<3>();
    grad[c.v[1]] += g.tail<3>();
  }
  double rg = 0.0, g2 = 0.0;
  for (int i = 0; i < 4; i++) {
    if (!mask[i]) continue;
    rg += volume[i] * Vector3d(res[i][0], res[i][1], res[i][2]).dot(grad[i]);
    g2 += grad[i].squaredNorm();
  }
  EXPECT_GT(g2, 0.0);
  EXPECT_NEAR(b.res_dot_grad, rg, 1e-12 * std::fabs(rg));
  EXPECT_NEAR(b.grad2, g2, 1e-12 * g2);
}

// The scene's extent: the bounding box's diagonal and the mean mass; split between two "ranks"
// and reduced (min, max, sum) it is the same as over all atoms at once
TEST(AdaptiveStiffness, SceneExtent)
{
  const double x[4][3] = {{0, 0, 0}, {3, 0, 1}, {1, 4, -1}, {2, 2, 11}};
  const double m[4] = {1.0, 2.0, 3.0, 6.0};
  SceneExtent one;
  for (int i = 0; i < 4; i++) one.add(x[i], m[i]);
  EXPECT_EQ(one.diagonal(), 13.0);    // 3 x 4 x 12
  EXPECT_EQ(one.mean_mass(), 3.0);
  SceneExtent a, b, all;
  a.add(x[0], m[0]);
  a.add(x[2], m[2]);
  b.add(x[1], m[1]);
  b.add(x[3], m[3]);
  for (int d = 0; d < 3; d++) {
    all.lo[d] = std::min(a.lo[d], b.lo[d]);
    all.hi[d] = std::max(a.hi[d], b.hi[d]);
  }
  for (int k = 0; k < 2; k++) all.mass[k] = a.mass[k] + b.mass[k];
  EXPECT_EQ(all.diagonal(), one.diagonal());
  EXPECT_EQ(all.mean_mass(), one.mean_mass());
  // a rank without atoms does not move the reduction; no atoms at all: no scales
  SceneExtent empty;
  EXPECT_TRUE(std::isnan(empty.mean_mass()));
  EXPECT_FALSE(empty.diagonal() > 0.0 && empty.mean_mass() > 0.0);
  EXPECT_EQ(one.error(), "");
  EXPECT_NE(empty.error(), "");
  // atoms without mass, or all at one point: the scales are unusable, the error says which
  SceneExtent massless, point;
  massless.add(x[0], 0.0);
  massless.add(x[3], 0.0);
  EXPECT_EQ(massless.error(),
            "kappa auto needs a group of atoms with mass that spans a box (its "
            "diagonal 11.3578, the mean mass 0)");
  point.add(x[1], 2.0);
  point.add(x[1], 4.0);
  EXPECT_EQ(point.error(),
            "kappa auto needs a group of atoms with mass that spans a box (its "
            "diagonal 0, the mean mass 3)");
  for (int d = 0; d < 3; d++) {
    EXPECT_EQ(std::min(one.lo[d], empty.lo[d]), one.lo[d]);
    EXPECT_EQ(std::max(one.hi[d], empty.hi[d]), one.hi[d]);
  }
}
