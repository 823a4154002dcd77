// Tests of the collision stencils (contact/stencil.h): each kind gives the same values, bit for
// bit, as the pair functions of distance.h, barrier.h, ccd.h and friction.h it stands for
// (zeros past a point-point pair's two points), its vertex counts, and closing() bounds how much
// a move shrinks the distance (sampled).

#include "contact/stencil.h"

#include "contact_test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::gaussian_points;
using PeriSISSMContactTest::Points;

namespace {

BarrierParameters reaching(double d)
{
  BarrierParameters prm;
  prm.kappa = 3.0;
  prm.dmin = 0.1 * d;
  prm.dhat = 2.0 * d;
  return prm;
}

}    // namespace

TEST(Stencil, KindsAndCounts)
{
  const CollisionStencil &pt = CollisionStencil::of(StencilType::kPointTriangle);
  const CollisionStencil &ee = CollisionStencil::of(StencilType::kEdgeEdge);
  const CollisionStencil &pp = CollisionStencil::of(StencilType::kPointPoint);
  EXPECT_EQ(pt.type(), StencilType::kPointTriangle);
  EXPECT_EQ(ee.type(), StencilType::kEdgeEdge);
  EXPECT_EQ(pp.type(), StencilType::kPointPoint);
  EXPECT_EQ(pt.num_vertices(), 4);
  EXPECT_EQ(ee.num_vertices(), 4);
  EXPECT_EQ(pp.num_vertices(), 2);
  EXPECT_EQ(pt.first_vertices(), 1);
  EXPECT_EQ(ee.first_vertices(), 2);
  EXPECT_EQ(pp.first_vertices(), 1);
  EXPECT_STREQ(pt.name(), "point-triangle");
  EXPECT_STREQ(ee.name(), "edge-edge");
  EXPECT_STREQ(pp.name(), "point-point");
}

TEST(Stencil, SameBitsAsThePairFunctions)
{
  std::mt19937_64 rng(5);
  const CollisionStencil &pt = CollisionStencil::of(StencilType::kPointTriangle);
  const CollisionStencil &ee = CollisionStencil::of(StencilType::kEdgeEdge);
  const CollisionStencil &pp = CollisionStencil::of(StencilType::kPointPoint);
  for (int trial = 0; trial < 50; trial++) {
    const Points x = gaussian_points(rng);
    const Points dx = gaussian_points(rng, 0.3);
    const Vector3d *y = x.data(), *dy = dx.data();
    const double eps = 0.05;
    CcdOptions opt;
    opt.dmin = 0.01;

    BarrierParameters prm = reaching(std::sqrt(point_triangle_distance2(y[0], y[1], y[2], y[3])));
    EXPECT_EQ(pt.distance2(y), point_triangle_distance2(y[0], y[1], y[2], y[3]));
    EXPECT_EQ(pt.barrier_energy(y, eps, prm),
              point_triangle_barrier_energy(y[0], y[1], y[2], y[3], prm));
    EXPECT_EQ(pt.barrier_gradient(y, eps, prm),
              point_triangle_barrier_gradient(y[0], y[1], y[2], y[3], prm));
    EXPECT_EQ(pt.barrier_hessian(y, eps, prm, true),
              point_triangle_barrier_hessian(y[0], y[1], y[2], y[3], prm, true));
    EXPECT_EQ(pt.ccd(y, dy, opt),
              point_triangle_ccd(y[0], y[1], y[2], y[3], dy[0], dy[1], dy[2], dy[3], opt));
    EXPECT_EQ(pt.friction_pair(y, eps, prm).lambda,
              point_triangle_friction_pair(y[0], y[1], y[2], y[3], prm).lambda);

    prm = reaching(std::sqrt(edge_edge_distance2(y[0], y[1], y[2], y[3])));
    EXPECT_EQ(ee.distance2(y), edge_edge_distance2(y[0], y[1], y[2], y[3]));
    EXPECT_EQ(ee.barrier_energy(y, eps, prm),
              edge_edge_barrier_energy(y[0], y[1], y[2], y[3], eps, prm));
    EXPECT_EQ(ee.barrier_gradient(y, eps, prm),
              edge_edge_barrier_gradient(y[0], y[1], y[2], y[3], eps, prm));
    EXPECT_EQ(ee.barrier_hessian(y, eps, prm, false),
              edge_edge_barrier_hessian(y[0], y[1], y[2], y[3], eps, prm, false));
    EXPECT_EQ(ee.ccd(y, dy, opt),
              edge_edge_ccd(y[0], y[1], y[2], y[3], dy[0], dy[1], dy[2], dy[3], opt));
    const FrictionPair fe = ee.friction_pair(y, eps, prm);
    const FrictionPair fd = edge_edge_friction_pair(y[0], y[1], y[2], y[3], eps, prm);
    EXPECT_EQ(fe.lambda, fd.lambda);
    EXPECT_EQ(fe.normal, fd.normal);
    EXPECT_EQ(fe.count, 4);

    prm = reaching(std::sqrt(point_point_distance2(y[0], y[1])));
    EXPECT_EQ(pp.distance2(y), point_point_distance2(y[0], y[1]));
    EXPECT_EQ(pp.barrier_energy(y, eps, prm), point_point_barrier_energy(y[0], y[1], prm));
    const Vector12d g = pp.barrier_gradient(y, eps, prm);
    EXPECT_EQ(Vector6d(g.head<6>()), point_point_barrier_gradient(y[0], y[1], prm));
    EXPECT_TRUE(g.tail<6>().isZero(0.0));
    const Matrix12d H = pp.barrier_hessian(y, eps, prm, true);
    const Matrix6d H6 = H.topLeftCorner<6, 6>();
    EXPECT_EQ(H6, point_point_barrier_hessian(y[0], y[1], prm, true));
    Matrix12d rest = H;
    rest.topLeftCorner<6, 6>().setZero();
    EXPECT_TRUE(rest.isZero(0.0));
    EXPECT_EQ(pp.ccd(y, dy, opt), point_point_ccd(y[0], y[1], dy[0], dy[1], opt));
    EXPECT_EQ(pp.friction_pair(y, eps, prm).count, 2);
  }
}

// A move of the points by at most len[k] shrinks the distance by at most closing(len): sampled
// over random pairs and random moves of each kind.
TEST(Stencil, ClosingBoundsTheDistanceChange)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (StencilType type :
       {StencilType::kPointTriangle, StencilType::kEdgeEdge, StencilType::kPointPoint}) {
    const CollisionStencil &s = CollisionStencil::of(type);
    int closer = 0;
    for (int trial = 0; trial < 300; trial++) {
      const Points x = gaussian_points(rng);
      Points dx = gaussian_points(rng, 0.5);
      double len[4];
      Points y;
      for (int k = 0; k < 4; k++) {
        dx[k] *= u01(rng);
        len[k] = dx[k].norm();
        y[k] = x[k] + dx[k];
      }
      const double d0 = std::sqrt(s.distance2(x.data())), d1 = std::sqrt(s.distance2(y.data()));
      EXPECT_GE(d1, d0 - s.closing(len) - 1e-12);
      closer += d1 < d0;
    }
    EXPECT_GT(closer, 30);
  }
  // the largest move of each primitive, summed
  const double len[4] = {0.1, 0.4, 0.2, 0.3};
  EXPECT_EQ(CollisionStencil::of(StencilType::kPointTriangle).closing(len), 0.1 + 0.4);
  EXPECT_EQ(CollisionStencil::of(StencilType::kEdgeEdge).closing(len), 0.4 + 0.3);
  EXPECT_EQ(CollisionStencil::of(StencilType::kPointPoint).closing(len), 0.1 + 0.4);
}
