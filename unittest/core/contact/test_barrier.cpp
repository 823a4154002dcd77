// Tests of the contact barrier (contact/barrier.h): b and its derivatives at the ends of its range
// and against finite differences, the chain rule through the squared distance with a thickness,
// the pair energies' gradients and Hessians (point-triangle, edge-edge with the mollifier,
// point-point) against finite differences over scales, the PSD projection, and the stiffness
// helpers.

#include "contact/barrier.h"

#include "contact/contact_test_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using namespace PeriSISSM;
using namespace PeriSISSMContactTest;

// b(dhat) = b'(dhat) = b''(dhat) = 0 exactly, and zero beyond: C1 (indeed C2) at dhat. Just
// inside, b ~ (dhat - g)^3 / dhat: b(dhat (1 - 1e-6)) ~ 1e-18 dhat^2.
TEST(Barrier, VanishesWithItsDerivativesAtDhat)
{
  for (double dhat : {1e-6, 1.0, 1e6}) {
    EXPECT_EQ(barrier(dhat, dhat), 0.0);
    EXPECT_EQ(barrier_first_derivative(dhat, dhat), 0.0);
    EXPECT_EQ(barrier_second_derivative(dhat, dhat), 0.0);
    EXPECT_EQ(barrier(2.0 * dhat, dhat), 0.0);
    EXPECT_EQ(barrier_first_derivative(2.0 * dhat, dhat), 0.0);
    const double g = dhat * (1.0 - 1e-6);
    EXPECT_GT(barrier(g, dhat), 0.0);
    EXPECT_LE(barrier(g, dhat), 1e-17 * dhat * dhat);
    EXPECT_LE(std::fabs(barrier_first_derivative(g, dhat)), 1e-11 * dhat);
    EXPECT_LE(std::fabs(barrier_second_derivative(g, dhat)), 1e-5);
  }
}

// b -> +inf as g -> 0: positive, decreasing, convex on (0, dhat); +inf at g <= 0.
TEST(Barrier, GrowsWithoutBoundAsTheGapCloses)
{
  const double dhat = 1e-3;
  double previous = 0.0;
  for (double r = 0.999; r > 1e-300; r *= 1e-3) {
    const double g = r * dhat;
    const double b = barrier(g, dhat);
    EXPECT_GT(b, previous) << r;
    EXPECT_LT(barrier_first_derivative(g, dhat), 0.0) << r;
    EXPECT_GT(barrier_second_derivative(g, dhat), 0.0) << r;
    previous = b;
  }
  EXPECT_GT(previous, 600.0 * dhat * dhat);    // -ln(1e-300) ~ 690
  EXPECT_EQ(barrier(0.0, dhat), INFINITY);
  EXPECT_EQ(barrier(-1.0, dhat), INFINITY);
}

// b' and b'' against central differences with step 1e-6 g (relative 1e-6 of the derivative
// asserted: truncation ~1e-12 relative, round-off ~ eps / 1e-6 ~ 1e-10), g / dhat from 1e-6 to
// 0.99, dhat from 1e-6 to 1e6.
TEST(Barrier, DerivativesMatchFiniteDifferences)
{
  for (double dhat : {1e-6, 1.0, 1e6})
    for (double r : {1e-6, 1e-3, 0.1, 0.5, 0.9, 0.99}) {
      const double g = r * dhat, h = 1e-6 * g;
      const double fd1 = (barrier(g + h, dhat) - barrier(g - h, dhat)) / (2.0 * h);
      const double fd2 =
          (barrier_first_derivative(g + h, dhat) - barrier_first_derivative(g - h, dhat)) /
          (2.0 * h);
      EXPECT_NEAR(barrier_first_derivative(g, dhat), fd1,
                  1e-6 * std::fabs(barrier_first_derivative(g, dhat)))
          << dhat << " " << r;
      EXPECT_NEAR(barrier_second_derivative(g, dhat), fd2,
                  1e-6 * std::fabs(barrier_second_derivative(g, dhat)))
          << dhat << " " << r;
    }
}

// B(D) = b(sqrt(D) - dmin): the value, and B', B'' against central differences in D with a step
// that moves d by 1e-4 of the gap (h = 2 d 1e-4 g). The gap sqrt(D) - dmin cancels when dmin is
// much larger than the gap: its relative round-off is ~ eps d / g (5e-11 at dmin = 0.5 L,
// g = 1e-6 L; a property of the barrier of a squared distance, not of the test), which the
// difference quotient amplifies to ~ 5e-11 |B| / (1e-4 g |B'|) ~ 5e-6; truncation is ~3e-9.
// Hence 1e-9 relative for the value and 1e-4 for the derivatives (measured 2.8e-5 at a step
// of 1e-6 g, 1.5e-6 at 1e-4 g).
TEST(Barrier, SquaredDistanceChainRule)
{
  for (double L : {1e-6, 1.0, 1e6}) {
    const double dhat = 1e-2 * L;
    for (double dmin : {0.0, 1e-3 * L, 0.5 * L})
      for (double r : {1e-4, 0.1, 0.5, 0.95}) {
        const double g = r * dhat, d = dmin + g, D = d * d, h = 2.0 * d * 1e-4 * g;
        EXPECT_NEAR(distance_barrier(D, dmin, dhat), barrier(g, dhat), 1e-9 * barrier(g, dhat));
        const double B1 = distance_barrier_first_derivative(D, dmin, dhat);
        const double B2 = distance_barrier_second_derivative(D, dmin, dhat);
        const double fd1 =
            (distance_barrier(D + h, dmin, dhat) - distance_barrier(D - h, dmin, dhat)) / (2.0 * h);
        const double fd2 = (distance_barrier_first_derivative(D + h, dmin, dhat) -
                            distance_barrier_first_derivative(D - h, dmin, dhat)) /
            (2.0 * h);
        EXPECT_NEAR(B1, fd1, 1e-4 * std::fabs(B1)) << L << " " << dmin << " " << r;
        EXPECT_NEAR(B2, fd2, 1e-4 * std::fabs(B2)) << L << " " << dmin << " " << r;
      }
    // beyond the reach dmin + dhat: zero
    EXPECT_EQ(distance_barrier(std::pow(1.1 * dhat, 2), 0.0, dhat), 0.0);
    EXPECT_EQ(distance_barrier_first_derivative(std::pow(1.1 * dhat, 2), 0.0, dhat), 0.0);
    EXPECT_EQ(distance_barrier_second_derivative(std::pow(1.1 * dhat, 2), 0.0, dhat), 0.0);
  }
}

// A point-triangle or edge-edge pair of scale L within the barrier's reach.
struct PairCase {
  Points x;
  BarrierParameters prm;
};

// From four Gaussian points (scale L, distance > 0.3 L), the point (or edge a) is translated
// rigidly along the distance's gradient until the gap is u dhat, u uniform in (0.05, 0.95);
// dhat = 0.1 L, dmin 0 or 0.05 L, kappa 3.7 / L^2 (energies ~ 1 at every scale).
template <class DistanceFn>
bool place_within_reach(Points &x, double L, std::mt19937_64 &rng, BarrierParameters &prm,
                        bool move_edge, DistanceFn distance)
{
  std::uniform_real_distribution<double> u(0.05, 0.95);
  prm.dhat = 0.1 * L;
  prm.dmin = u(rng) < 0.5 ? 0.0 : 0.05 * L;
  prm.kappa = 3.7 / (L * L);
  if (!(distance(x) > 0.3 * L)) return false;
  const double target = prm.dmin + u(rng) * prm.dhat;
  for (int iter = 0; iter < 4; iter++) {
    const double dd = distance(x);
    // the gradient of d under a rigid translation of the moving points (numerical)
    Vector3d grad;
    for (int k = 0; k < 3; k++) {
      Points p = x, m = x;
      const double h = 1e-7 * L;
      for (int v = 0; v < (move_edge ? 2 : 1); v++) {
        p[v](k) += h;
        m[v](k) -= h;
      }
      grad(k) = (distance(p) - distance(m)) / (2.0 * h);
    }
    if (!(grad.norm() > 0.5)) return false;
    for (int v = 0; v < (move_edge ? 2 : 1); v++) x[v] -= (dd - target) * grad / grad.norm();
  }
  return std::fabs(distance(x) - target) < 1e-6 * L;
}

// Gradient and Hessian of kappa b of a pair against central differences (step 1e-6 of the gap:
// the barrier varies on the scale of the gap, so the step follows it). Asserted: 1e-5 relative to
// the largest entry (measured <= 5e-8 over scales 1e-6 .. 1e6, printed).
template <class Energy, class Gradient, class Hessian>
void pair_fd(Energy E, Gradient G, Hessian H, const PairCase &c, double gap, double &worst_g,
             double &worst_h)
{
  const X12 x = pack(c.x);
  const double h = 1e-6 * gap;
  const std::function<double(const X12 &)> f = [&](const X12 &y) {
    return E(unpack(y));
  };
  const std::function<X12(const X12 &)> g = [&](const X12 &y) {
    return G(unpack(y));
  };
  const X12 g0 = g(x);
  const M12 H0 = H(unpack(x));
  const double eg = relative_error(g0, fd_gradient<12>(f, x, h), 1e-300);
  const double eh = relative_error(H0, fd_hessian<12>(g, x, h), 1e-300);
  EXPECT_LE(eg, 1e-5);
  EXPECT_LE(eh, 1e-5);
  worst_g = std::max(worst_g, eg);
  worst_h = std::max(worst_h, eh);
}

TEST(Barrier, PointTrianglePairMatchesFiniteDifferences)
{
  std::mt19937_64 rng(31);
  for (double L : {1e-6, 1.0, 1e6}) {
    int tested = 0;
    double wg = 0.0, wh = 0.0;
    for (int trial = 0; trial < 300 && tested < 40; trial++) {
      PairCase c;
      c.x = gaussian_points(rng, L);
      auto dist = [](const Points &x) {
        return point_triangle_distance(x[0], x[1], x[2], x[3]);
      };
      if (!place_within_reach(c.x, L, rng, c.prm, false, dist)) continue;
      tested++;
      const double gap = dist(c.x) - c.prm.dmin;
      const BarrierParameters prm = c.prm;
      pair_fd(
          [&](const Points &x) {
            return point_triangle_barrier_energy(x[0], x[1], x[2], x[3], prm);
          },
          [&](const Points &x) {
            return point_triangle_barrier_gradient(x[0], x[1], x[2], x[3], prm);
          },
          [&](const Points &x) {
            return point_triangle_barrier_hessian(x[0], x[1], x[2], x[3], prm, false);
          },
          c, gap, wg, wh);
      EXPECT_GT(point_triangle_barrier_energy(c.x[0], c.x[1], c.x[2], c.x[3], prm), 0.0);
    }
    EXPECT_GE(tested, 40);
    std::printf("point-triangle barrier, scale %g: worst FD error gradient %.1e Hessian %.1e\n", L,
                wg, wh);
  }
}

// Edge-edge pairs, with the mollifier's threshold eps either small (unmollified: e = 1) or
// above the pair's c (mollified: e < 1), so that both terms of the product rule are tested.
TEST(Barrier, EdgeEdgePairMatchesFiniteDifferences)
{
  std::mt19937_64 rng(32);
  for (double L : {1e-6, 1.0, 1e6}) {
    int tested = 0, mollified = 0;
    double wg = 0.0, wh = 0.0;
    for (int trial = 0; trial < 400 && tested < 60; trial++) {
      PairCase c;
      c.x = gaussian_points(rng, L);
      auto dist = [](const Points &x) {
        return edge_edge_distance(x[0], x[1], x[2], x[3]);
      };
      if (!place_within_reach(c.x, L, rng, c.prm, true, dist)) continue;
      tested++;
      const double cval = (c.x[1] - c.x[0]).cross(c.x[3] - c.x[2]).squaredNorm();
      const double eps = tested % 2 ? 1e-3 * cval : 2.0 * cval;
      if (edge_edge_mollifier(c.x[0], c.x[1], c.x[2], c.x[3], eps) < 1.0) mollified++;
      const double gap = dist(c.x) - c.prm.dmin;
      const BarrierParameters prm = c.prm;
      pair_fd(
          [&](const Points &x) {
            return edge_edge_barrier_energy(x[0], x[1], x[2], x[3], eps, prm);
          },
          [&](const Points &x) {
            return edge_edge_barrier_gradient(x[0], x[1], x[2], x[3], eps, prm);
          },
          [&](const Points &x) {
            return edge_edge_barrier_hessian(x[0], x[1], x[2], x[3], eps, prm, false);
          },
          c, gap, wg, wh);
    }
    EXPECT_GE(tested, 60);
    EXPECT_GE(mollified, 25);
    std::printf("edge-edge barrier, scale %g (%d of %d mollified): worst FD error gradient "
                "%.1e Hessian %.1e\n",
                L, mollified, tested, wg, wh);
  }
}

// Exactly parallel edges within reach: the mollifier is 0, so are energy and gradient; the
// Hessian is finite (B times the mollifier's Hessian, which is not zero at c = 0).
TEST(Barrier, ParallelEdgesHaveNoEnergy)
{
  const Vector3d a0(0, 0, 0), a1(1, 0, 0), b0(0.2, 0, 0.05), b1(0.9, 0, 0.05);
  BarrierParameters prm;
  prm.dhat = 0.1;
  const double eps = edge_edge_mollifier_threshold(a0, a1, Vector3d(0, 0, 0), Vector3d(0, 1, 0));
  EXPECT_EQ(edge_edge_barrier_energy(a0, a1, b0, b1, eps, prm), 0.0);
  EXPECT_EQ(edge_edge_barrier_gradient(a0, a1, b0, b1, eps, prm).norm(), 0.0);
  EXPECT_TRUE(edge_edge_barrier_hessian(a0, a1, b0, b1, eps, prm, false).allFinite());
  EXPECT_TRUE(edge_edge_barrier_hessian(a0, a1, b0, b1, eps, prm, true).allFinite());
}

TEST(Barrier, PointPointPair)
{
  BarrierParameters prm;
  prm.kappa = 2.0;
  prm.dhat = 0.1;
  prm.dmin = 0.5;
  const Vector3d p(0, 0, 0), q(0.3, 0.4, 0.0);    // d = 0.5 + 0: gap 0 -> inf; move q out
  const Vector3d q2 = 1.1 * q;                    // d = 0.55, gap 0.05
  EXPECT_NEAR(point_point_barrier_energy(p, q2, prm), 2.0 * barrier(0.05, 0.1), 1e-15);
  EXPECT_EQ(point_point_barrier_energy(p, q, prm), INFINITY);
  EXPECT_EQ(point_point_barrier_energy(p, 1.3 * q, prm), 0.0);    // gap 0.15 > dhat
  // the force pushes q away from p along the line: gradient on q along +q, on p along -q
  const Vector6d g = point_point_barrier_gradient(p, q2, prm);
  EXPECT_LT(g.tail<3>().dot(q), 0.0);    // energy decreases when q moves away
  EXPECT_NEAR((g.head<3>() + g.tail<3>()).norm(), 0.0, 1e-12 * g.norm());
  // Hessian against finite differences of the gradient
  using V6 = Eigen::Matrix<double, 6, 1>;
  const std::function<V6(const V6 &)> gf = [&](const V6 &y) {
    return point_point_barrier_gradient(y.head<3>(), y.tail<3>(), prm);
  };
  V6 x;
  x << p, q2;
  EXPECT_LE(relative_error(point_point_barrier_hessian(p, q2, prm, false),
                           fd_hessian<6>(gf, x, 1e-8), 1e-300),
            1e-6);
}

// Projection: PSD (smallest eigenvalue >= -1e-12 of the largest), unchanged for a PSD matrix,
// and H - P(H) negative semi-definite (only negative directions removed).
TEST(Barrier, ProjectedHessianIsPositiveSemiDefinite)
{
  std::mt19937_64 rng(33);
  int indefinite = 0;
  for (int trial = 0; trial < 200; trial++) {
    PairCase c;
    c.x = gaussian_points(rng, 1.0);
    auto dist = [](const Points &x) {
      return point_triangle_distance(x[0], x[1], x[2], x[3]);
    };
    if (!place_within_reach(c.x, 1.0, rng, c.prm, false, dist)) continue;
    const Points &x = c.x;
    const Matrix12d H = point_triangle_barrier_hessian(x[0], x[1], x[2], x[3], c.prm, false);
    const Matrix12d P = point_triangle_barrier_hessian(x[0], x[1], x[2], x[3], c.prm, true);
    Eigen::SelfAdjointEigenSolver<Matrix12d> eh(H), ep(P), ed(H - P);
    const double scale = eh.eigenvalues().cwiseAbs().maxCoeff();
    if (eh.eigenvalues().minCoeff() < -1e-10 * scale) indefinite++;
    EXPECT_GE(ep.eigenvalues().minCoeff(), -1e-12 * scale);
    EXPECT_LE(ed.eigenvalues().maxCoeff(), 1e-12 * scale);
    EXPECT_LE((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
  }
  EXPECT_GE(indefinite, 10);    // the test saw indefinite Hessians to project
  Matrix12d A = Matrix12d::Random();
  const Matrix12d S = A * A.transpose();
  EXPECT_LE((project_to_psd(S) - S).cwiseAbs().maxCoeff(), 1e-12 * S.cwiseAbs().maxCoeff());
}

// kappa_min from b''(1e-8 diagonal), clamping of the gradient-balance estimate, and the update.
TEST(Barrier, StiffnessHelpers)
{
  const double diag = 2.0, dhat = 1e-3, mass = 0.01;
  double kappa_max = 0.0;
  const double kmin_expected = 1e11 * mass / barrier_second_derivative(2e-8, dhat);
  // no barrier gradient: kappa_min
  EXPECT_DOUBLE_EQ(initial_barrier_stiffness(diag, dhat, mass, 0.0, 0.0, kappa_max), kmin_expected);
  EXPECT_DOUBLE_EQ(kappa_max, 100.0 * kmin_expected);
  // balance within the bounds: -gE.gB / |gB|^2
  EXPECT_DOUBLE_EQ(
      initial_barrier_stiffness(diag, dhat, mass, -5.0 * kmin_expected, 1.0, kappa_max),
      5.0 * kmin_expected);
  // clamped above and below
  EXPECT_DOUBLE_EQ(
      initial_barrier_stiffness(diag, dhat, mass, -1e3 * kmin_expected, 1.0, kappa_max), kappa_max);
  EXPECT_DOUBLE_EQ(initial_barrier_stiffness(diag, dhat, mass, 1.0, 1.0, kappa_max), kmin_expected);
  // doubling while the smallest gap is tiny and shrinking, capped
  EXPECT_EQ(update_barrier_stiffness(1e-9, 5e-10, 10.0, 3.0, diag), 6.0);
  EXPECT_EQ(update_barrier_stiffness(1e-9, 5e-10, 10.0, 6.0, diag), 10.0);
  EXPECT_EQ(update_barrier_stiffness(5e-10, 1e-9, 10.0, 3.0, diag), 3.0);    // growing
  EXPECT_EQ(update_barrier_stiffness(1e-3, 5e-4, 10.0, 3.0, diag), 3.0);     // not tiny
}

}    // namespace
