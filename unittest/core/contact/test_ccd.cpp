// Tests of additive CCD (contact/ccd.h): exact cases with known contact times (a point falling
// onto a triangle, edges crossing, parallel, collinear and degenerate edges,
// point-point), no contact, zero motion, pairs that start within the thickness, the iteration
// cap; random pairs whose distance is sampled densely over [0, t] (never below dmin) and over
// [0, 1] (t before any sampled crossing); the same pairs scaled by 1e-6 and 1e6.

#include "contact/ccd.h"

#include "contact/contact_test_helpers.h"
#include "contact/distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace {

using namespace PeriSISSM;
using namespace PeriSISSMContactTest;

// ---- exact cases ----

// For a head-on approach at constant speed, l (the bound on the approach rate) is the true rate,
// and ACCD's answer is (1 - s) t_true up to round-off: the first sub-step goes to (1 - s) t_true,
// where the gap is s g0, and the next would go below it. Asserted:
// (1 - s) t_true (1 - 1e-12) <= t <= t_true.
void expect_head_on(double t, double t_true, double s, const char *what)
{
  EXPECT_LE(t, t_true) << what;
  EXPECT_GE(t, (1.0 - s) * t_true * (1.0 - 1e-12)) << what;
}

// The point p = (0.2, 0.3, h0) falls onto the triangle (0,0,0), (1,0,0), (0,1,0) (its interior
// below p) with displacement -2 h0 z (point moving, triangle moving up, or both): the distance
// reaches dmin at t_true = (h0 - dmin) / (2 h0).
TEST(Ccd, PointFallingOntoTriangleInterior)
{
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  for (double h0 : {1.0, 1e-3})
    for (double dmin_rel : {0.0, 0.1, 0.5})
      for (double s : {0.1, 0.5})
        for (int who = 0; who < 3; who++) {
          const Vector3d p(0.2, 0.3, h0);
          const double dmin = dmin_rel * h0;
          // who = 0: the point falls; 1: the triangle rises; 2: both, halfway each
          const double fp = who == 0 ? 1.0 : who == 1 ? 0.0 : 0.5;
          const Vector3d dp(0, 0, -2.0 * h0 * fp), dt(0, 0, 2.0 * h0 * (1.0 - fp));
          CcdOptions opt;
          opt.dmin = dmin;
          opt.s = s;
          CcdReport rep;
          const double t = point_triangle_ccd(p, t0, t1, t2, dp, dt, dt, dt, opt, &rep);
          expect_head_on(t, (h0 - dmin) / (2.0 * h0), s, "point onto triangle");
          EXPECT_FALSE(rep.capped);
          EXPECT_EQ(rep.iterations, 2);
        }
}

// The point moves parallel to the triangle's plane at height 0.1 (over the face, then beyond
// its edge): the distance never falls, t = 1.
TEST(Ccd, PointMovingParallelToTriangle)
{
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0), zero = Vector3d::Zero();
  for (double dmin : {0.0, 0.05}) {
    CcdOptions opt;
    opt.dmin = dmin;
    CcdReport rep;
    const double t = point_triangle_ccd(Vector3d(0.2, 0.2, 0.1), t0, t1, t2,
                                        Vector3d(0.5, 0.3, 0.0), zero, zero, zero, opt, &rep);
    EXPECT_EQ(t, 1.0);
    std::printf("point parallel to a triangle (gap %.2f, motion 0.58): %ld sub-steps\n", 0.1 - dmin,
                rep.iterations);
  }
}

// Edge a along x at z = 0, edge b along y at z = 1 moving by -2 z: they cross at t = 1/2, the
// distance reaches dmin at (1 - dmin) / 2.
TEST(Ccd, PerpendicularEdgesCrossing)
{
  const Vector3d a0(-1, 0, 0), a1(1, 0, 0), b0(0, -1, 1), b1(0, 1, 1), zero = Vector3d::Zero();
  const Vector3d db(0, 0, -2);
  for (double dmin : {0.0, 0.01, 0.3}) {
    CcdOptions opt;
    opt.dmin = dmin;
    const double t = edge_edge_ccd(a0, a1, b0, b1, zero, zero, db, db, opt);
    expect_head_on(t, (1.0 - dmin) / 2.0, opt.s, "perpendicular edges");
  }
}

// Exactly parallel edges, one above the other, approaching head-on: the distance is the same at
// every point of the overlap (the closest points are not unique), t_true = (1 - dmin) / 2.
TEST(Ccd, ParallelEdgesApproaching)
{
  const Vector3d a0(0, 0, 0), a1(1, 0, 0), b0(0.2, 0, 1), b1(1.2, 0, 1), zero = Vector3d::Zero();
  const Vector3d db(0, 0, -2);
  for (double dmin : {0.0, 0.01}) {
    CcdOptions opt;
    opt.dmin = dmin;
    const double t = edge_edge_ccd(a0, a1, b0, b1, zero, zero, db, db, opt);
    expect_head_on(t, (1.0 - dmin) / 2.0, opt.s, "parallel edges");
  }
}

// Collinear edges on the x axis, b moving by -3 x through a (the degenerate crossing: the edges
// would overlap): end to end at t_true = (1 - dmin) / 3, head-on.
TEST(Ccd, CollinearEdgesPassingThroughEachOther)
{
  const Vector3d a0(0, 0, 0), a1(1, 0, 0), b0(2, 0, 0), b1(3, 0, 0), zero = Vector3d::Zero();
  const Vector3d db(-3, 0, 0);
  for (double dmin : {0.0, 0.01}) {
    CcdOptions opt;
    opt.dmin = dmin;
    const double t = edge_edge_ccd(a0, a1, b0, b1, zero, zero, db, db, opt);
    expect_head_on(t, (1.0 - dmin) / 3.0, opt.s, "collinear edges");
  }
}

// Parallel edges 0.1 apart sliding into each other along their direction (b from x in [2, 3] to
// [-1, 0]): the distance falls from sqrt(1.01) to 0.1 at t = 1/3 and stays 0.1 while they
// overlap. With dmin = 0.05 they never touch; ACCD stops when the gap would fall below s g0
// (here 0.0955, at t = (1 - sqrt(0.1455^2 - 0.01)) / 3 = 0.2981): t is at most that, the
// distance stays above dmin on [0, t].
TEST(Ccd, ParallelEdgesSlidingIntoEachOther)
{
  const Vector3d a0(0, 0, 0), a1(1, 0, 0), b0(2, 0.1, 0), b1(3, 0.1, 0), zero = Vector3d::Zero();
  const Vector3d db(-3, 0, 0);
  CcdOptions opt;
  opt.dmin = 0.05;
  CcdReport rep;
  const double t = edge_edge_ccd(a0, a1, b0, b1, zero, zero, db, db, opt, &rep);
  const double keep = opt.s * (std::sqrt(1.01) - opt.dmin);
  const double t_keep = (1.0 - std::sqrt(std::pow(opt.dmin + keep, 2) - 0.01)) / 3.0;
  EXPECT_LE(t, t_keep);
  EXPECT_GE(t, 0.2);
  for (int k = 0; k <= 1000; k++) {
    const double tau = t * k / 1000.0;
    EXPECT_GT(edge_edge_distance(a0, a1, b0 + tau * db, b1 + tau * db), opt.dmin);
  }
  std::printf("parallel edges sliding in: t = %.4f (gap s g0 reached at %.4f), %ld sub-steps\n", t,
              t_keep, rep.iterations);
  // with dmin = 0 and s small enough that s g0 < 0.1 they never come within s g0: t = 1
  opt.dmin = 0.0;
  opt.s = 0.05;
  EXPECT_EQ(edge_edge_ccd(a0, a1, b0, b1, zero, zero, db, db, opt), 1.0);
}

// Degenerate edge-edge pairs: an edge of zero length (a point) falling head-on onto the middle
// of another edge behaves as the point-edge pair it is (t = (1 - s) t_true); an edge that
// shrinks to a point during the move while it approaches (its ends meeting at the crossing)
// never gets within dmin on [0, t], and t is not later than the first contact.
TEST(Ccd, DegenerateEdges)
{
  const Vector3d zero = Vector3d::Zero();
  const Vector3d a0(0.5, 0, 1), b0(0, 0, 0), b1(1, 0, 0), da(0, 0, -2);
  for (double dmin : {0.0, 0.01}) {
    CcdOptions opt;
    opt.dmin = dmin;
    const double t = edge_edge_ccd(a0, a0, b0, b1, da, da, zero, zero, opt);
    expect_head_on(t, (1.0 - dmin) / 2.0, opt.s, "zero-length edge");
  }
  // a from (0.3, 0.2, 1)-(0.7, -0.2, 1) to the single point (0.5, 0, -1): its ends close at the
  // rate its midpoint falls; the midpoint is the closest point, so contact at t = (1 - dmin) / 2
  const Vector3d c0(0.3, 0.2, 1), c1(0.7, -0.2, 1), end(0.5, 0, -1);
  CcdOptions opt;
  opt.dmin = 0.01;
  const double t = edge_edge_ccd(c0, c1, b0, b1, end - c0, end - c1, zero, zero, opt);
  const double t_true = (1.0 - opt.dmin) / 2.0;
  EXPECT_LE(t, t_true);
  EXPECT_GT(t, 0.0);
  for (int k = 0; k <= 1000; k++) {
    const double tau = t * k / 1000.0;
    EXPECT_GT(edge_edge_distance(c0 + tau * (end - c0), c1 + tau * (end - c1), b0, b1), opt.dmin);
  }
}

TEST(Ccd, PointPoint)
{
  for (double dmin : {0.0, 0.2}) {
    CcdOptions opt;
    opt.dmin = dmin;
    // two particles head-on
    expect_head_on(point_point_ccd(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(1, 0, 0),
                                   Vector3d(-1, 0, 0), opt),
                   (1.0 - dmin) / 2.0, opt.s, "point-point");
    // passing each other at 0.5 > dmin: no contact... unless within s g0 (0.05 .. 0.08): t = 1
    EXPECT_EQ(point_point_ccd(Vector3d(0, 0, 0), Vector3d(1, 0.5, 0), Vector3d(1, 0, 0),
                              Vector3d(-1, 0, 0), opt),
              1.0);
  }
}

// No relative motion (none at all, or the same translation for every point): t = 1 at once.
TEST(Ccd, ZeroMotion)
{
  const Vector3d p(0.2, 0.2, 0.01), t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0), zero = Vector3d::Zero();
  const Vector3d move(3.0, -2.0, 7.0);
  CcdReport rep;
  EXPECT_EQ(point_triangle_ccd(p, t0, t1, t2, zero, zero, zero, zero, CcdOptions(), &rep), 1.0);
  EXPECT_EQ(rep.iterations, 0);
  EXPECT_EQ(point_triangle_ccd(p, t0, t1, t2, move, move, move, move, CcdOptions(), &rep), 1.0);
  EXPECT_EQ(rep.iterations, 0);
  EXPECT_EQ(edge_edge_ccd(t0, t1, p, t2, move, move, move, move, CcdOptions(), &rep), 1.0);
  EXPECT_EQ(rep.iterations, 0);
}

// A pair that starts at distance <= dmin: t = 0, flagged, no sub-step (no hang).
TEST(Ccd, AlreadyWithinThickness)
{
  const Vector3d p(0.2, 0.2, 0.01), t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0), zero = Vector3d::Zero();
  const Vector3d away(0, 0, 1);
  CcdOptions opt;
  opt.dmin = 0.02;
  CcdReport rep;
  EXPECT_EQ(point_triangle_ccd(p, t0, t1, t2, away, zero, zero, zero, opt, &rep), 0.0);
  EXPECT_TRUE(rep.initially_close);
  EXPECT_EQ(rep.iterations, 0);
  // touching exactly, dmin = 0
  opt.dmin = 0.0;
  EXPECT_EQ(
      point_triangle_ccd(Vector3d(0.2, 0.2, 0.0), t0, t1, t2, away, zero, zero, zero, opt, &rep),
      0.0);
  EXPECT_TRUE(rep.initially_close);
  // intersecting edges
  EXPECT_EQ(edge_edge_ccd(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 0),
                          Vector3d(0, 1, 0), zero, zero, away, away, opt, &rep),
            0.0);
  EXPECT_TRUE(rep.initially_close);
}

// The slow case of ACCD: a pair that starts close and moves far. A point at gap 1e-4 above a
// large triangle slides 1 along it: the gap never falls, each sub-step is 0.9 g / l, about
// l / (0.9 g) = 1.1e4 of them; t = 1. With a cap of 1000 the answer is the last safe time,
// flagged, and the distance stays above dmin up to it.
TEST(Ccd, SlowCaseAndIterationCap)
{
  const Vector3d t0(-10, -10, 0), t1(10, -10, 0), t2(0, 10, 0), zero = Vector3d::Zero();
  const Vector3d p(0, 0, 1e-4), dp(1.0, 0.0, 0.0);
  CcdReport rep;
  EXPECT_EQ(point_triangle_ccd(p, t0, t1, t2, dp, zero, zero, zero, CcdOptions(), &rep), 1.0);
  EXPECT_FALSE(rep.capped);
  EXPECT_NEAR(rep.iterations, 1.0 / (0.9 * 1e-4), 0.01 / (0.9 * 1e-4));
  std::printf("gap 1e-4, sliding 1: %ld sub-steps\n", rep.iterations);
  CcdOptions opt;
  opt.max_iterations = 1000;
  const double t = point_triangle_ccd(p, t0, t1, t2, dp, zero, zero, zero, opt, &rep);
  EXPECT_TRUE(rep.capped);
  EXPECT_EQ(rep.iterations, 1000);
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 1.0);
  EXPECT_GT(point_triangle_distance(p + t * dp, t0, t1, t2), 0.0);
}

// ---- random pairs ----

// A random pair: the four points uniform in the unit cube, displacements Gaussian (sd 0.6),
// dmin in {0, 1e-3, 0.02}. When aimed, the second primitive's displacement gets a common
// translation that makes a random point of it (barycentric / edge parameter) meet a random point
// of the first one at a time uniform in (0.1, 1.3): then most pairs make contact within the step.
struct Motion {
  Points x, dx;
  double dmin;
};

Motion random_motion(std::mt19937_64 &rng, bool edges = false, bool aimed = false)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Motion m;
  for (int k = 0; k < 4; k++) {
    m.x[k] = Vector3d(u(rng), u(rng), u(rng));
    m.dx[k] = gaussian_point(rng, 0.6);
  }
  const double dmins[3] = {0.0, 1e-3, 0.02};
  m.dmin = dmins[int(3.0 * u(rng)) % 3];
  if (aimed) {
    const double tc = 0.1 + 1.2 * u(rng);
    // weights of the points of primitive A (first) and B (second) at the meeting point
    double w[4];
    if (edges) {
      const double a = u(rng), b = u(rng);
      w[0] = 1.0 - a, w[1] = a, w[2] = 1.0 - b, w[3] = b;
    } else {
      double b1 = u(rng), b2 = u(rng);
      if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
      w[0] = 1.0, w[1] = 1.0 - b1 - b2, w[2] = b1, w[3] = b2;
    }
    const int ka = edges ? 2 : 1;
    Vector3d pa = Vector3d::Zero(), pb = Vector3d::Zero();
    for (int k = 0; k < 4; k++) (k < ka ? pa : pb) += w[k] * (m.x[k] + tc * m.dx[k]);
    for (int k = ka; k < 4; k++) m.dx[k] += (pa - pb) / tc;
  }
  return m;
}

Points at(const Motion &m, double t)
{
  return {m.x[0] + t * m.dx[0], m.x[1] + t * m.dx[1], m.x[2] + t * m.dx[2], m.x[3] + t * m.dx[3]};
}

double pt_distance(const Points &y)
{
  return point_triangle_distance(y[0], y[1], y[2], y[3]);
}
double ee_distance(const Points &y)
{
  return edge_edge_distance(y[0], y[1], y[2], y[3]);
}

double pt_ccd(const Motion &m, const CcdOptions &opt, CcdReport *rep)
{
  return point_triangle_ccd(m.x[0], m.x[1], m.x[2], m.x[3], m.dx[0], m.dx[1], m.dx[2], m.dx[3], opt,
                            rep);
}

double ee_ccd(const Motion &m, const CcdOptions &opt, CcdReport *rep)
{
  return edge_edge_ccd(m.x[0], m.x[1], m.x[2], m.x[3], m.dx[0], m.dx[1], m.dx[2], m.dx[3], opt,
                       rep);
}

// 2000 pairs, every other one aimed. Sampled at 1000 sub-steps over [0, t]: the distance never
// falls below dmin (the guarantee;
// 1e-12 of the scene's size allowed for the round-off of the sampled positions). Sampled at
// 1000 sub-steps over [0, 1]: when some sample is within dmin (a contact the step would make),
// t is before the first such sample; the crossing time is refined by bisection to measure how
// early t is (t / t_cross, printed with the sub-step counts).
void random_pairs(double (*distance)(const Points &),
                  double (*ccd)(const Motion &, const CcdOptions &, CcdReport *), const char *name,
                  bool edges, unsigned seed)
{
  std::mt19937_64 rng(seed);
  const int n = 2000, samples = 1000;
  int crossing = 0, skipped = 0;
  long total_iterations = 0, max_iterations = 0;
  std::vector<double> ratio;
  for (int trial = 0; trial < n; trial++) {
    const Motion m = random_motion(rng, edges, trial % 2 == 1);
    if (!(distance(m.x) > m.dmin)) {
      skipped++;
      continue;
    }
    CcdOptions opt;
    opt.dmin = m.dmin;
    CcdReport rep;
    const double t = ccd(m, opt, &rep);
    EXPECT_FALSE(rep.capped) << trial;
    total_iterations += rep.iterations;
    max_iterations = std::max(max_iterations, rep.iterations);
    for (int k = 0; k <= samples; k++)
      ASSERT_GE(distance(at(m, t * k / samples)), m.dmin - 1e-12) << name << " " << trial;
    double first = -1.0;
    for (int k = 1; k <= samples && first < 0.0; k++)
      if (distance(at(m, double(k) / samples)) <= m.dmin) first = double(k) / samples;
    if (first < 0.0) continue;
    crossing++;
    EXPECT_LT(t, first) << name << " " << trial;
    double lo = first - 1.0 / samples, hi = first;
    for (int it = 0; it < 60; it++) {
      const double mid = 0.5 * (lo + hi);
      (distance(at(m, mid)) <= m.dmin ? hi : lo) = mid;
    }
    ratio.push_back(t / hi);
  }
  std::sort(ratio.begin(), ratio.end());
  EXPECT_GE(crossing, n / 4);
  std::printf("%s: %d pairs (%d started within dmin), %d make contact within the step; "
              "sub-steps mean %.1f max %ld; t / t_contact min %.3f median %.3f max %.3f\n",
              name, n - skipped, skipped, crossing, double(total_iterations) / (n - skipped),
              max_iterations, ratio.front(), ratio[ratio.size() / 2], ratio.back());
}

TEST(Ccd, RandomPointTrianglePairsStayApart)
{
  random_pairs(pt_distance, pt_ccd, "point-triangle", false, 41);
}

TEST(Ccd, RandomEdgeEdgePairsStayApart)
{
  random_pairs(ee_distance, ee_ccd, "edge-edge", true, 42);
}

double pair_ccd(bool pt, const Motion &m, const CcdOptions &opt, CcdReport *rep = nullptr)
{
  return pt ? pt_ccd(m, opt, rep) : ee_ccd(m, opt, rep);
}

// The random pairs of the tests below: point-triangle and edge-edge in turn, every other pair of
// each kind aimed; check(trial, pt, motion, opt, t) for each, opt with the pair's dmin and t its
// CCD fraction with those options
template <class Check> void alternating_pairs(unsigned seed, int n, Check check)
{
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < n; trial++) {
    const bool pt = trial % 2 == 0;
    const Motion m = random_motion(rng, !pt, trial % 4 >= 2);
    CcdOptions opt;
    opt.dmin = m.dmin;
    check(trial, pt, m, opt, pair_ccd(pt, m, opt));
  }
}

// ---- the step's end ----

// An earlier end t_max gives the same sub-steps up to it: t = min(t at t_max = 1, t_max) bit
// for bit, over 2000 random pairs (every other one aimed) and ends from 1e-3 to 0.7; a first
// sub-step that already reaches t_max returns it without a look at a distance (0 iterations).
TEST(Ccd, AnEarlierEndCutsTheSameSubSteps)
{
  int without_a_look = 0;
  alternating_pairs(44, 2000, [&](int trial, bool pt, const Motion &m, CcdOptions opt, double t) {
    for (double t_max : {0.7, 0.2, 0.03, 1e-3}) {
      opt.t_max = t_max;
      CcdReport rep;
      EXPECT_EQ(pair_ccd(pt, m, opt, &rep), std::min(t, t_max)) << trial << " t_max " << t_max;
      without_a_look += rep.iterations == 0 && !rep.initially_close;
    }
  });
  EXPECT_GT(without_a_look, 1000);
  // a move of 1e11 (a diverged iterate) whose end is cut to 1e-13 first
  const Vector3d t0(-1, -1, 0), t1(1, -1, 0), t2(0, 1, 0), zero = Vector3d::Zero();
  CcdOptions opt;
  opt.t_max = 1e-13;
  CcdReport rep;
  EXPECT_EQ(point_triangle_ccd(Vector3d(0, 0, 0.5), t0, t1, t2, Vector3d(1e11, 0, 0), zero, zero,
                               zero, opt, &rep),
            1e-13);
  EXPECT_EQ(rep.iterations, 0);
}

// ---- scale ----

// Positions, displacements and dmin times 1e-6 and 1e6: t is a ratio of lengths, unchanged up
// to round-off unless a comparison (the stop test g < s g0, a class of the distance) flips on
// a near tie. Measured: the largest relative change over 2000 + 2000 random pairs (printed);
// asserted 1e-9.
TEST(Ccd, ScaleInvariance)
{
  double worst = 0.0;
  alternating_pairs(43, 4000, [&](int trial, bool pt, const Motion &m, CcdOptions opt, double t) {
    for (double s : {1e-6, 1e6}) {
      Motion ms = m;
      for (int k = 0; k < 4; k++) {
        ms.x[k] *= s;
        ms.dx[k] *= s;
      }
      CcdOptions os = opt;
      os.dmin = s * m.dmin;
      const double ts = pair_ccd(pt, ms, os);
      const double rel = t > 0.0 ? std::fabs(ts - t) / t : std::fabs(ts);
      EXPECT_LE(rel, 1e-9) << trial << " scale " << s;
      worst = std::max(worst, rel);
    }
  });
  std::printf("largest relative change of t under scaling by 1e-6 and 1e6: %.1e\n", worst);
}

}    // namespace
