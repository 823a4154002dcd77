// Tests of the contact distances (contact/distance.h): the closest-feature classes on hand cases
// of every region, the distances against brute force on random configurations, gradients and
// Hessians against central finite differences over scales 1e-6 .. 1e6, the mollifier, and
// parallel edges and degenerate primitives (finite values, no NaN).

#include "contact/distance.h"

#include "contact/contact_test_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

namespace {

using namespace PeriSISSM;
using namespace PeriSISSMContactTest;

const double kScales[] = {1e-6, 1e-3, 1.0, 1e3, 1e6};

// ---- the test's own closest points (independent of the library's classification) ----

// distance of p to segment e0 e1 by the clamped projection parameter
double segment_distance(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  const Vector3d e = e1 - e0;
  const double ee = e.squaredNorm();
  double t = ee > 0.0 ? (p - e0).dot(e) / ee : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return (p - e0 - t * e).norm();
}

// point-triangle by dense sampling of the triangle: the minimum over the (n + 1)(n + 2) / 2
// points of a barycentric grid. Every point of the triangle is within (longest edge) / n of a
// grid point, so d <= brute <= d + longest / n.
double point_triangle_brute(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                            const Vector3d &t2, int n)
{
  double best = INFINITY;
  for (int i = 0; i <= n; i++)
    for (int j = 0; i + j <= n; j++) {
      const Vector3d q = t0 + (double(i) / n) * (t1 - t0) + (double(j) / n) * (t2 - t0);
      best = std::min(best, (p - q).norm());
    }
  return best;
}

// edge-edge by dense sampling of edge a, each sample's exact distance to segment b: within
// |a1 - a0| / n of the true distance (the distance to b is 1-Lipschitz along a), never below.
double edge_edge_brute(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                       const Vector3d &b1, int n)
{
  double best = INFINITY;
  for (int i = 0; i <= n; i++)
    best = std::min(best, segment_distance(a0 + (double(i) / n) * (a1 - a0), b0, b1));
  return best;
}

double longest_edge(const Vector3d &t0, const Vector3d &t1, const Vector3d &t2)
{
  return std::max((t1 - t0).norm(), std::max((t2 - t1).norm(), (t0 - t2).norm()));
}

// ---- hand cases ----

// The triangle (0,0,0), (1,0,0), (0,1,0) and a point in each of the seven regions, at height
// 0.3 above the plane (0.5 for the face).
TEST(Distance, PointTriangleHandCases)
{
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  struct Case {
    Vector3d p;
    PointTriangleType type;
    double d2;
  };
  const double h2 = 0.09;
  const Case cases[] = {
      {Vector3d(0.2, 0.2, 0.5), PointTriangleType::kFace, 0.25},
      {Vector3d(0.2, 0.2, -0.5), PointTriangleType::kFace, 0.25},
      {Vector3d(-1, -1, 0.3), PointTriangleType::kT0, 2.0 + h2},
      {Vector3d(2, -1, 0.3), PointTriangleType::kT1, 2.0 + h2},
      {Vector3d(-1, 2, 0.3), PointTriangleType::kT2, 2.0 + h2},
      {Vector3d(0.5, -1, 0.3), PointTriangleType::kE01, 1.0 + h2},
      {Vector3d(1, 1, 0.3), PointTriangleType::kE12, 0.5 + h2},
      {Vector3d(-1, 0.5, 0.3), PointTriangleType::kE20, 1.0 + h2},
  };
  for (const Case &c : cases) {
    EXPECT_EQ(point_triangle_type(c.p, t0, t1, t2), c.type) << c.p.transpose();
    EXPECT_NEAR(point_triangle_distance2(c.p, t0, t1, t2), c.d2, 1e-15) << c.p.transpose();
    EXPECT_NEAR(point_triangle_distance(c.p, t0, t1, t2), std::sqrt(c.d2), 1e-15);
  }
}

// Edge a = (0,0,0)-(1,0,0); edge b at height h in each of the nine classes.
TEST(Distance, EdgeEdgeHandCases)
{
  const Vector3d a0(0, 0, 0), a1(1, 0, 0);
  const double h = 0.3, h2 = 0.09;
  struct Case {
    Vector3d b0, b1;
    EdgeEdgeType type;
    double d2;
  };
  const Case cases[] = {
      // crossing above a's middle
      {Vector3d(0.4, -1, h), Vector3d(0.4, 1, h), EdgeEdgeType::kInterior, h2},
      // b beyond a's ends, crossing a's line: an end of a against b's interior
      {Vector3d(-1, -1, h), Vector3d(-1, 1, h), EdgeEdgeType::kA0B, 1.0 + h2},
      {Vector3d(2, -1, h), Vector3d(2, 1, h), EdgeEdgeType::kA1B, 1.0 + h2},
      // b starting beside a's middle and going away: b's end against a's interior
      {Vector3d(0.5, 0.3, h), Vector3d(0.5, 2, h), EdgeEdgeType::kAB0, 0.09 + h2},
      {Vector3d(0.5, 2, h), Vector3d(0.5, 0.3, h), EdgeEdgeType::kAB1, 0.09 + h2},
      // end points: b going away from a corner
      {Vector3d(-0.5, -0.5, h), Vector3d(-2, -2, h), EdgeEdgeType::kA0B0, 0.5 + h2},
      {Vector3d(-2, -2, h), Vector3d(-0.5, -0.5, h), EdgeEdgeType::kA0B1, 0.5 + h2},
      {Vector3d(1.5, -0.5, h), Vector3d(3, -2, h), EdgeEdgeType::kA1B0, 0.5 + h2},
      {Vector3d(3, -2, h), Vector3d(1.5, -0.5, h), EdgeEdgeType::kA1B1, 0.5 + h2},
  };
  for (const Case &c : cases) {
    EXPECT_EQ(edge_edge_type(a0, a1, c.b0, c.b1), c.type) << c.b0.transpose();
    EXPECT_NEAR(edge_edge_distance2(a0, a1, c.b0, c.b1), c.d2, 1e-15) << c.b0.transpose();
    EXPECT_NEAR(edge_edge_distance(a0, a1, c.b0, c.b1), std::sqrt(c.d2), 1e-15);
  }
  // exactly parallel, overlapping: an end point against the other's interior, distance h
  const Vector3d b0(0.2, 0, h), b1(1.5, 0, h);
  EXPECT_NEAR(edge_edge_distance2(a0, a1, b0, b1), h2, 1e-15);
  EXPECT_NE(edge_edge_type(a0, a1, b0, b1), EdgeEdgeType::kInterior);
}

TEST(Distance, PointEdgeHandCases)
{
  const Vector3d e0(0, 0, 0), e1(2, 0, 0);
  EXPECT_EQ(point_edge_type(Vector3d(-1, 1, 0), e0, e1), PointEdgeType::kE0);
  EXPECT_EQ(point_edge_type(Vector3d(3, 1, 0), e0, e1), PointEdgeType::kE1);
  EXPECT_EQ(point_edge_type(Vector3d(1, 1, 1), e0, e1), PointEdgeType::kInterior);
  EXPECT_NEAR(point_edge_distance2(Vector3d(-1, 1, 0), e0, e1), 2.0, 1e-15);
  EXPECT_NEAR(point_edge_distance2(Vector3d(3, 1, 0), e0, e1), 2.0, 1e-15);
  EXPECT_NEAR(point_edge_distance2(Vector3d(1, 1, 1), e0, e1), 2.0, 1e-15);
  EXPECT_NEAR(point_edge_distance(Vector3d(1, 1, 1), e0, e1), std::sqrt(2.0), 1e-15);
}

// ---- brute force ----

// Random Gaussian points at several scales (seeded): the squared distance and the plain distance
// against dense sampling, d <= brute <= d + longest / n (n = 300), and the plain distance
// against the square root of the classified squared distance (1e-10 relative: the two differ
// by round-off only, except very close to a plane or line where the smooth formula loses digits
// relative to d; d >= 1e-3 of the scale here).
TEST(Distance, PointTriangleMatchesBruteForce)
{
  std::mt19937_64 rng(15);
  const int n = 300;
  std::map<PointTriangleType, int> seen;
  for (double L : {1e-6, 1.0, 1e6})
    for (int trial = 0; trial < 150; trial++) {
      const Points x = gaussian_points(rng, L);
      const double d = point_triangle_distance(x[0], x[1], x[2], x[3]);
      const double d2 = point_triangle_distance2(x[0], x[1], x[2], x[3]);
      const double brute = point_triangle_brute(x[0], x[1], x[2], x[3], n);
      EXPECT_GE(brute, d * (1.0 - 1e-14)) << trial;
      EXPECT_LE(brute, d + longest_edge(x[1], x[2], x[3]) / n) << trial;
      if (d > 1e-3 * L) { EXPECT_NEAR(std::sqrt(d2), d, 1e-10 * d) << trial; }
      seen[point_triangle_type(x[0], x[1], x[2], x[3])]++;
    }
  EXPECT_EQ(seen.size(), 7u);    // every class came up
}

TEST(Distance, EdgeEdgeMatchesBruteForce)
{
  std::mt19937_64 rng(16);
  const int n = 20000;
  std::map<EdgeEdgeType, int> seen;
  for (double L : {1e-6, 1.0, 1e6})
    for (int trial = 0; trial < 300; trial++) {
      const Points x = gaussian_points(rng, L);
      const double d = edge_edge_distance(x[0], x[1], x[2], x[3]);
      const double d2 = edge_edge_distance2(x[0], x[1], x[2], x[3]);
      const double brute = edge_edge_brute(x[0], x[1], x[2], x[3], n);
      EXPECT_GE(brute, d * (1.0 - 1e-14)) << trial;
      EXPECT_LE(brute, d + (x[1] - x[0]).norm() / n) << trial;
      if (d > 1e-3 * L) { EXPECT_NEAR(std::sqrt(d2), d, 1e-10 * d) << trial; }
      seen[edge_edge_type(x[0], x[1], x[2], x[3])]++;
    }
  EXPECT_EQ(seen.size(), 9u);
}

// ---- derivatives against finite differences ----

// Central differences with step h = 1e-5 L at scale L: truncation ~ h^2 |f'''| ~ 1e-10 of the
// derivative's size, round-off ~ eps |f| / h ~ 1e-11 of it, for shapes that are not degenerate
// (triangles with sin(angle)^2 >= 1e-2, edges at sin^2 >= 1e-2, distances >= 1e-2 L). The
// measured errors are 1e-11 .. 2e-8, and 1.3e-7 once (a point-plane Hessian at scale 1e-6),
// printed below; 1e-6 relative to the derivative's size (gradient: its largest entry or L;
// Hessian: its largest entry or 1) is asserted.
struct FdError {
  double gradient = 0.0, hessian = 0.0;
};

template <int N> using Vec = Eigen::Matrix<double, N, 1>;
template <int N> using Mat = Eigen::Matrix<double, N, N>;

template <int N>
FdError fd_errors(const std::function<double(const Vec<N> &)> &f,
                  const std::function<Vec<N>(const Vec<N> &)> &g,
                  const std::function<Mat<N>(const Vec<N> &)> &H, const Vec<N> &x, double L)
{
  const double h = 1e-5 * L;
  FdError e;
  e.gradient = relative_error(g(x), fd_gradient<N>(f, x, h), L);
  e.hessian = relative_error(H(x), fd_hessian<N>(g, x, h), 1.0);
  return e;
}

bool good_triangle(const Vector3d &t0, const Vector3d &t1, const Vector3d &t2)
{
  const Vector3d b = t1 - t0, c = t2 - t0;
  return b.cross(c).squaredNorm() >= 1e-2 * b.squaredNorm() * c.squaredNorm();
}

bool good_edges(const Points &x)
{
  const Vector3d u = x[1] - x[0], v = x[3] - x[2];
  return u.cross(v).squaredNorm() >= 1e-2 * u.squaredNorm() * v.squaredNorm();
}

TEST(Distance, BuildingBlockDerivativesMatchFiniteDifferences)
{
  std::mt19937_64 rng(17);
  using V6 = Eigen::Matrix<double, 6, 1>;
  using V9 = Eigen::Matrix<double, 9, 1>;
  for (double L : kScales) {
    FdError worst[4];
    for (int trial = 0; trial < 40; trial++) {
      const Points x = gaussian_points(rng, L);
      if (!good_triangle(x[1], x[2], x[3]) || !good_edges(x)) continue;
      if (point_line_distance2(x[0], x[1], x[2]) < 1e-4 * L * L) continue;
      FdError e[4];
      e[0] = fd_errors<6>(
          [](const V6 &y) {
            return point_point_distance2(y.head<3>(), y.tail<3>());
          },
          [](const V6 &y) {
            return point_point_distance2_gradient(y.head<3>(), y.tail<3>());
          },
          [](const V6 &y) {
            return point_point_distance2_hessian(y.head<3>(), y.tail<3>());
          },
          pack(x).head<6>(), L);
      e[1] = fd_errors<9>(
          [](const V9 &y) {
            return point_line_distance2(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6));
          },
          [](const V9 &y) {
            return point_line_distance2_gradient(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6));
          },
          [](const V9 &y) {
            return point_line_distance2_hessian(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6));
          },
          pack(x).head<9>(), L);
      e[2] = fd_errors<12>(
          [](const X12 &y) {
            const Points p = unpack(y);
            return point_plane_distance2(p[0], p[1], p[2], p[3]);
          },
          [](const X12 &y) {
            const Points p = unpack(y);
            return point_plane_distance2_gradient(p[0], p[1], p[2], p[3]);
          },
          [](const X12 &y) {
            const Points p = unpack(y);
            return point_plane_distance2_hessian(p[0], p[1], p[2], p[3]);
          },
          pack(x), L);
      e[3] = fd_errors<12>(
          [](const X12 &y) {
            const Points p = unpack(y);
            return line_line_distance2(p[0], p[1], p[2], p[3]);
          },
          [](const X12 &y) {
            const Points p = unpack(y);
            return line_line_distance2_gradient(p[0], p[1], p[2], p[3]);
          },
          [](const X12 &y) {
            const Points p = unpack(y);
            return line_line_distance2_hessian(p[0], p[1], p[2], p[3]);
          },
          pack(x), L);
      for (int k = 0; k < 4; k++) {
        EXPECT_LE(e[k].gradient, 1e-6) << "block " << k << " scale " << L;
        EXPECT_LE(e[k].hessian, 1e-6) << "block " << k << " scale " << L;
        worst[k].gradient = std::max(worst[k].gradient, e[k].gradient);
        worst[k].hessian = std::max(worst[k].hessian, e[k].hessian);
      }
    }
    std::printf("scale %g: worst relative FD error (gradient, Hessian): point-point %.1e %.1e, "
                "point-line %.1e %.1e, point-plane %.1e %.1e, line-line %.1e %.1e\n",
                L, worst[0].gradient, worst[0].hessian, worst[1].gradient, worst[1].hessian,
                worst[2].gradient, worst[2].hessian, worst[3].gradient, worst[3].hessian);
  }
}

// The classified distances on random configurations of every class: a configuration is used
// only when all the finite-difference points fall in the same class (a change of class is a C1
// seam where the Hessian jumps).
template <class Type>
void classified_fd(const std::function<Type(const Points &)> &type,
                   const std::function<double(const Points &)> &f,
                   const std::function<X12(const Points &)> &g,
                   const std::function<M12(const Points &)> &H,
                   const std::function<bool(const Points &)> &usable, unsigned seed, size_t classes)
{
  std::mt19937_64 rng(seed);
  for (double L : kScales) {
    std::map<Type, int> tested;
    FdError worst;
    for (int trial = 0; trial < 400; trial++) {
      const Points x = gaussian_points(rng, L);
      if (!usable(x)) continue;
      const Type t = type(x);
      const double h = 1e-5 * L;
      bool same = true;
      for (int i = 0; i < 12 && same; i++)
        for (double sgn : {-1.0, 1.0}) {
          X12 y = pack(x);
          y(i) += sgn * h;
          if (type(unpack(y)) != t) same = false;
        }
      if (!same) continue;
      tested[t]++;
      const FdError e = fd_errors<12>(
          [&](const X12 &y) {
            return f(unpack(y));
          },
          [&](const X12 &y) {
            return g(unpack(y));
          },
          [&](const X12 &y) {
            return H(unpack(y));
          },
          pack(x), L);
      EXPECT_LE(e.gradient, 1e-6) << "class " << int(t) << " scale " << L;
      EXPECT_LE(e.hessian, 1e-6) << "class " << int(t) << " scale " << L;
      worst.gradient = std::max(worst.gradient, e.gradient);
      worst.hessian = std::max(worst.hessian, e.hessian);
    }
    EXPECT_EQ(tested.size(), classes) << "scale " << L;
    std::printf("scale %g: %zu classes, worst relative FD error gradient %.1e Hessian %.1e\n", L,
                tested.size(), worst.gradient, worst.hessian);
  }
}

TEST(Distance, PointTriangleDerivativesMatchFiniteDifferences)
{
  classified_fd<PointTriangleType>(
      [](const Points &x) {
        return point_triangle_type(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        return point_triangle_distance2(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        return point_triangle_distance2_gradient(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        return point_triangle_distance2_hessian(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        const double L = (x[1] - x[2]).norm();
        return good_triangle(x[1], x[2], x[3]) &&
            point_triangle_distance(x[0], x[1], x[2], x[3]) > 1e-2 * L;
      },
      18, 7);
}

TEST(Distance, EdgeEdgeDerivativesMatchFiniteDifferences)
{
  classified_fd<EdgeEdgeType>(
      [](const Points &x) {
        return edge_edge_type(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        return edge_edge_distance2(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        return edge_edge_distance2_gradient(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        return edge_edge_distance2_hessian(x[0], x[1], x[2], x[3]);
      },
      [](const Points &x) {
        const double L = (x[1] - x[0]).norm();
        return good_edges(x) && edge_edge_distance(x[0], x[1], x[2], x[3]) > 1e-2 * L;
      },
      19, 9);
}

// ---- the mollifier ----

// e(c) = 1 with zero derivatives at c >= eps; C1 at c = eps (the values and gradients just
// below approach 1 and 0); gradient and Hessian against finite differences for c < eps.
TEST(Distance, MollifierIsC1AndMatchesFiniteDifferences)
{
  std::mt19937_64 rng(20);
  for (double L : kScales) {
    const Vector3d a0 = gaussian_point(rng, L), a1 = a0 + Vector3d(L, 0, 0);
    const Vector3d b0 = gaussian_point(rng, L);
    const double eps = edge_edge_mollifier_threshold(a0, a1, b0, b0 + Vector3d(0, L, 0));
    // b at angle phi to a: c = L^4 sin^2(phi), eps = 1e-3 L^4
    for (double sin2 : {0.0, 1e-8, 1e-5, 2e-4, 5e-4, 9.99e-4, 1.01e-3, 0.5}) {
      const double phi = std::asin(std::sqrt(sin2));
      const Vector3d b1 = b0 + L * Vector3d(std::cos(phi), std::sin(phi), 0.0);
      const Points x = {a0, a1, b0, b1};
      const double c = (a1 - a0).cross(b1 - b0).squaredNorm();
      const double e = edge_edge_mollifier(a0, a1, b0, b1, eps);
      EXPECT_TRUE(std::isfinite(e));
      EXPECT_GE(e, 0.0);
      EXPECT_LE(e, 1.0);
      if (c >= eps) {
        EXPECT_EQ(e, 1.0);
        EXPECT_EQ(edge_edge_mollifier_gradient(a0, a1, b0, b1, eps).norm(), 0.0);
        continue;
      }
      EXPECT_NEAR(e, (2.0 - c / eps) * c / eps, 1e-14);
      const std::function<double(const X12 &)> f = [&](const X12 &y) {
        const Points p = unpack(y);
        return edge_edge_mollifier(p[0], p[1], p[2], p[3], eps);
      };
      const std::function<X12(const X12 &)> g = [&](const X12 &y) {
        const Points p = unpack(y);
        return edge_edge_mollifier_gradient(p[0], p[1], p[2], p[3], eps);
      };
      // the mollifier is dimensionless: its gradient ~ 1 / L, Hessian ~ 1 / L^2; errors
      // relative to the derivative's largest entry, or 1 / L and 1 / L^2 when smaller. It is
      // strongly curved (e'' = -2 / eps^2 with eps = 1e-3 L^4): just below the threshold its
      // gradient is small (e' -> 0) and h = 1e-5 L leaves a truncation error ~1e-5 of it, so
      // h = 1e-7 L here (truncation ~1e-9, round-off ~1e-8 relative).
      const double h = 1e-7 * L;
      EXPECT_LE(relative_error(g(pack(x)), fd_gradient<12>(f, pack(x), h), 1.0 / L), 1e-6)
          << sin2 << " " << L;
      EXPECT_LE(relative_error(edge_edge_mollifier_hessian(a0, a1, b0, b1, eps),
                               fd_hessian<12>(g, pack(x), h), 1.0 / (L * L)),
                1e-6)
          << sin2 << " " << L;
    }
    // C1 at the threshold: e -> 1 and de -> 0 from below
    const double phi = std::asin(std::sqrt(1e-3 * (1.0 - 1e-9)));
    const Vector3d b1 = b0 + L * Vector3d(std::cos(phi), std::sin(phi), 0.0);
    EXPECT_NEAR(edge_edge_mollifier(a0, a1, b0, b1, eps), 1.0, 1e-15);
    EXPECT_LE(edge_edge_mollifier_gradient(a0, a1, b0, b1, eps).norm() * L, 1e-6);
  }
}

// ---- parallel edges and degenerate primitives ----

// Edge b at angle theta to a in the plane z = h, over a's middle: the distance is h whatever
// theta (0 included), never NaN; gradient and Hessian finite. Measured (printed at L = 1): the
// plain distance stays at round-off (< 1e-15 relative) for every theta; the smooth line-line
// formula's error grows as theta falls (4e-14 at 1e-4, 2e-12 at 1e-6, 3e-11 at 1e-7; bounded by
// about eps_mach / sin(theta)) until the classification switches to end points at
// sin^2 < 1e-16, where it is exact again. Asserted: 1e-12 and 1e-8 relative.
TEST(Distance, NearlyParallelEdgesStayFinite)
{
  const double h = 0.3;
  // a generic rigid motion, so that the coordinates carry round-off
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.77, Vector3d(0.3, -1.0, 0.6).normalized()).toRotationMatrix();
  const Vector3d shift(0.123, -0.456, 0.789);
  for (double L : {1e-6, 1.0, 1e6}) {
    const Vector3d a0 = L * shift, a1 = L * (R * Vector3d(1, 0, 0) + shift);
    for (double theta : {1e-2, 1e-4, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-12, 1e-15, 0.0}) {
      // b crosses a's line (seen along z) at 0.37 of a
      const Vector3d dir(std::cos(theta), std::sin(theta), 0.0);
      const Vector3d mid(0.37, 0.0, h);
      const Vector3d b0 = L * (R * (mid - 0.3 * dir) + shift);
      const Vector3d b1 = L * (R * (mid + 0.3 * dir) + shift);
      const double d2 = edge_edge_distance2(a0, a1, b0, b1);
      const double d = edge_edge_distance(a0, a1, b0, b1);
      const Vector12d g = edge_edge_distance2_gradient(a0, a1, b0, b1);
      const Matrix12d H = edge_edge_distance2_hessian(a0, a1, b0, b1);
      EXPECT_TRUE(std::isfinite(d2) && std::isfinite(d));
      EXPECT_TRUE(g.allFinite()) << theta;
      EXPECT_TRUE(H.allFinite()) << theta;
      EXPECT_NEAR(d, h * L, 1e-12 * L) << theta;
      EXPECT_NEAR(std::sqrt(d2), h * L, 1e-8 * L) << theta;
      if (L == 1.0)
        std::printf("theta %.0e: class %d, |sqrt(d2) - h| / h = %.1e, |d - h| / h = %.1e\n", theta,
                    int(edge_edge_type(a0, a1, b0, b1)), std::fabs(std::sqrt(d2) - h) / h,
                    std::fabs(d - h) / h);
    }
  }
}

// Degenerate triangles (collinear vertices, two or three coincident) and edges of zero length:
// the distance is that of the segments / points they are (brute force), gradients and Hessians
// are finite. A triangle of zero area is classified as its edges (never the face, whose normal
// is zero); a zero-length edge as its end point.
TEST(Distance, DegeneratePrimitivesStayFinite)
{
  const Vector3d p(0.3, 0.7, 0.4);
  const std::vector<std::array<Vector3d, 3>> triangles = {
      {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 0, 0)},                // collinear
      {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0, 0)},              // collinear, inside
      {Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(1, 1, 0)},                // two coincident
      {Vector3d(0.1, 0.2, 0), Vector3d(0.1, 0.2, 0), Vector3d(0.1, 0.2, 0)},    // a point
  };
  for (const auto &t : triangles) {
    const double brute =
        std::min(segment_distance(p, t[0], t[1]),
                 std::min(segment_distance(p, t[1], t[2]), segment_distance(p, t[2], t[0])));
    EXPECT_NE(point_triangle_type(p, t[0], t[1], t[2]), PointTriangleType::kFace);
    EXPECT_NEAR(point_triangle_distance(p, t[0], t[1], t[2]), brute, 1e-15);
    EXPECT_NEAR(point_triangle_distance2(p, t[0], t[1], t[2]), brute * brute, 1e-15);
    EXPECT_TRUE(point_triangle_distance2_gradient(p, t[0], t[1], t[2]).allFinite());
    EXPECT_TRUE(point_triangle_distance2_hessian(p, t[0], t[1], t[2]).allFinite());
  }
  // the point on a degenerate triangle (distance 0): finite too
  const auto &t = triangles[0];
  const Vector3d on(1.5, 0, 0);
  EXPECT_EQ(point_triangle_distance2(on, t[0], t[1], t[2]), 0.0);
  EXPECT_TRUE(point_triangle_distance2_hessian(on, t[0], t[1], t[2]).allFinite());

  const Vector3d a0(0, 0, 0), a1(1, 0, 0), z(0.5, 0.5, 0.5);
  // b of zero length: the distance of its point to a
  EXPECT_NEAR(edge_edge_distance2(a0, a1, z, z), 0.5, 1e-15);
  EXPECT_TRUE(edge_edge_distance2_hessian(a0, a1, z, z).allFinite());
  // both of zero length
  EXPECT_NEAR(edge_edge_distance2(a0, a0, z, z), 0.75, 1e-15);
  EXPECT_TRUE(edge_edge_distance2_hessian(a0, a0, z, z).allFinite());
  EXPECT_TRUE(edge_edge_distance2_gradient(a0, a0, z, z).allFinite());
  // collinear overlapping edges (distance 0, parallel)
  EXPECT_EQ(edge_edge_distance2(a0, a1, Vector3d(0.5, 0, 0), Vector3d(2, 0, 0)), 0.0);
  EXPECT_TRUE(
      edge_edge_distance2_hessian(a0, a1, Vector3d(0.5, 0, 0), Vector3d(2, 0, 0)).allFinite());
  // point-edge with a zero-length edge
  EXPECT_NEAR(point_edge_distance2(z, a0, a0), 0.75, 1e-15);
  EXPECT_TRUE(point_edge_distance2_hessian(z, a0, a0).allFinite());
}

// ---- scale ----

// All coordinates times 1e-6 and 1e6: squared distances scale by the square, to round-off.
// Scaling by 1e+-6 is not exact in binary, so the inputs change by ~1e-16 relative and the
// smooth formulas amplify that by their condition (a point close to a large triangle: the
// triple product cancels); measured 1.8e-12 at worst over 500 Gaussian configurations, 1e-10
// asserted. A class can only change on an exact tie, which random points miss.
TEST(Distance, ScaleCovariance)
{
  std::mt19937_64 rng(21);
  double worst = 0.0;
  for (int trial = 0; trial < 500; trial++) {
    const Points x = gaussian_points(rng);
    const double pt = point_triangle_distance2(x[0], x[1], x[2], x[3]);
    const double ee = edge_edge_distance2(x[0], x[1], x[2], x[3]);
    for (double s : {1e-6, 1e6}) {
      Points y;
      for (int k = 0; k < 4; k++) y[k] = s * x[k];
      const double rpt = point_triangle_distance2(y[0], y[1], y[2], y[3]) / (s * s * pt) - 1.0;
      const double ree = edge_edge_distance2(y[0], y[1], y[2], y[3]) / (s * s * ee) - 1.0;
      worst = std::max(worst, std::max(std::fabs(rpt), std::fabs(ree)));
      EXPECT_EQ(point_triangle_type(y[0], y[1], y[2], y[3]),
                point_triangle_type(x[0], x[1], x[2], x[3]));
      EXPECT_EQ(edge_edge_type(y[0], y[1], y[2], y[3]), edge_edge_type(x[0], x[1], x[2], x[3]));
    }
  }
  std::printf("worst relative change of the squared distances under scaling: %.1e\n", worst);
  EXPECT_LE(worst, 1e-10);
}

}    // namespace
