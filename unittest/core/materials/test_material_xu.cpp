// The SISSM authors' membrane model "xu": the defining formulas above s_c, the C2 continuation
// below (values, slopes and curvatures continuous at s_c, Phat = dW/ds on both sides, restoring,
// c >= 0), accuracy near rest and the small-strain constants E = 2 s0, nu = 0.

#include "materials/material_linear.h"
#include "materials/material_xu.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using Eigen::Vector3d;
using PeriSISSM::kXuThreshold;
using PeriSISSM::XuMaterial;

constexpr double kS0 = 8000.0;    // the s0 of the SISSM authors' tablecloth scene

// g(s) = (s^4 - 1)/4 + (s^-2 - 1)/2 and its derivatives as defined (s > 0).
double g_def(double s)
{
  return 0.25 * (std::pow(s, 4) - 1.0) + 0.5 * (std::pow(s, -2) - 1.0);
}
double g1_def(double s)
{
  return std::pow(s, 3) - std::pow(s, -3);
}
double g2_def(double s)
{
  return 3.0 * s * s + 3.0 * std::pow(s, -4);
}

// Above s_c, W and Phat are the authors' formulas: relative 1e-14 of the terms' magnitude (the
// defining form cancels near s = 1, the implemented one does not).
TEST(XuMaterial, MatchesDefiningFormAboveThreshold)
{
  const XuMaterial m(kS0);
  std::mt19937_64 rng(1701u);
  for (int i = 0; i < 500; ++i) {
    Vector3d s;
    double terms = 0.0, pterms = 0.0;
    for (int k = 0; k < 3; ++k) {
      s(k) = PeriSISSMTest::uniform(rng, kXuThreshold, 4.0);
      terms += 0.25 * (std::pow(s(k), 4) + 1.0) + 0.5 * (std::pow(s(k), -2) + 1.0);
      pterms += std::pow(s(k), 3) + std::pow(s(k), -3);
    }
    const double W = kS0 / 3.0 * (g_def(s(0)) + g_def(s(1)) + g_def(s(2)));
    EXPECT_NEAR(m.energy(s), W, 1e-14 * kS0 * terms) << s.transpose();
    const Vector3d P = m.principal_stress(s);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(P(k), kS0 / 3.0 * g1_def(s(k)), 1e-14 * kS0 * pterms) << s.transpose();
  }
  EXPECT_EQ(m.mu(), kS0);
  EXPECT_EQ(m.s0(), kS0);
  EXPECT_EQ(m.lambda(), 0.0);
  EXPECT_STREQ(m.name(), "xu");
}

// Near rest g(1 + e) = e^2 (3 + 5e + 15/4 e^2 + 3/2 e^3 + 1/4 e^4) / (1 + e)^2 exactly (the
// defining form times s^2 is (s^2 - 1)^2 (s^2 + 2) / 4): W keeps round-off accuracy relative to
// itself, where the defining form has relative error ~eps / e^2 (~1 at e = 1e-8).
TEST(XuMaterial, EnergyAccurateNearRest)
{
  for (double e : {1e-10, -1e-8, 1e-6, -1e-4, 1e-2}) {
    const double s = 1.0 + e;
    const double ex = s - 1.0;    // exact
    const double ref = ex * ex * (3.0 + ex * (5.0 + ex * (3.75 + ex * (1.5 + 0.25 * ex)))) /
        ((1.0 + ex) * (1.0 + ex));
    EXPECT_NEAR(XuMaterial::stretch_energy(s), ref, 1e-14 * ref) << "e = " << e;
    // g'(1 + e) = 6 e + O(e^2), to round-off relative to itself
    const double slope_ref = g1_def(s);    // s^3 - s^-3 has no harmful cancellation at |e| >= 1e-6
    if (std::abs(e) >= 1e-6) {
      EXPECT_NEAR(XuMaterial::stretch_slope(s), slope_ref, 1e-9 * std::abs(slope_ref));
    }
    EXPECT_NEAR(XuMaterial::stretch_slope(s), 6.0 * ex, 1e-14 + 10.0 * ex * ex) << "e = " << e;
  }
  const XuMaterial m(kS0);
  EXPECT_EQ(m.energy(Vector3d::Ones()), 0.0);
  EXPECT_EQ(m.principal_stress(Vector3d::Ones()), Vector3d::Zero());
}

// C2 at s_c: on each side g agrees with the Taylor polynomial built from the defining g, g',
// g'' at s_c to the cubic remainder |g'''|max d^3 / 6 (g''' = 6 s below; 6 s - 12 s^-5 above,
// |g'''| <= 4940 on [s_c, s_c + 1e-3]), and g' with its linear one to |g'''|max d^2 / 2. A jump J
// in g, g' or g'' would show as an error J, J d or J d^2 / 2, above these bounds for
// J >~ 1e-9.
TEST(XuMaterial, ContinuationIsC2AtThreshold)
{
  const double sc = kXuThreshold;
  const double g0 = g_def(sc), g1 = g1_def(sc), g2 = g2_def(sc);
  for (double d : {1e-3, 1e-4, 1e-5}) {
    for (int side : {-1, 1}) {
      const double x = side * d;
      const double g3max = side < 0 ? 6.0 * sc : 4940.0;
      const double roundoff = 1e-14 * (std::abs(g0) + std::abs(g1) + g2);
      EXPECT_NEAR(XuMaterial::stretch_energy(sc + x), g0 + g1 * x + 0.5 * g2 * x * x,
                  g3max * d * d * d / 6.0 + roundoff)
          << "d = " << x;
      EXPECT_NEAR(XuMaterial::stretch_slope(sc + x), g1 + g2 * x, g3max * d * d / 2.0 + roundoff)
          << "d = " << x;
    }
  }
  // at s_c itself: the defining values
  EXPECT_NEAR(XuMaterial::stretch_energy(sc), g0, 1e-15 * g0);
  EXPECT_NEAR(XuMaterial::stretch_slope(sc), g1, 1e-15 * std::abs(g1));
  // curvature just below s_c (second differences, exact for the quadratic h; g''' = 6 s adds
  // < 6 s h): the one-sided limits equal g''(s_c)
  const double h = 1e-4;
  const auto slope = [](double s) {
    return XuMaterial::stretch_slope(s);
  };
  const double below = (slope(sc - h) - slope(sc - 2.0 * h)) / h;
  const double above = (slope(sc + 2.0 * h) - slope(sc + h)) / h;
  EXPECT_NEAR(below, g2, 6.0 * sc * 2.0 * h + 1e-8 * g2);
  EXPECT_NEAR(above, g2, 4940.0 * 2.0 * h + 1e-8 * g2);
}

// Phat = dW/ds by central differences, h = 1e-6, on both sides of s_c, at 0 and for inverted
// (negative) singular values, one entry at a time in a 3-vector with the others arbitrary.
// Truncation s0/3 h^2 |g'''| / 6 <= 3e-10 s0 (|g'''| <= 4940 near s_c; 6 |s| elsewhere, below
// 1e-8 |P| at |s| = 50), round-off eps |W| / h ~ 2e-10 |W|: tolerance 1e-8 |P| + 1e-9 (|W| + s0).
TEST(XuMaterial, StressIsEnergyGradientAcrossThreshold)
{
  const XuMaterial m(kS0);
  const std::vector<double> values = {-50.0,  -3.0, -1.0,   -0.31, -1e-3, 0.0, 1e-3, 0.1,
                                      0.2999, 0.3,  0.3001, 0.31,  0.5,   1.0, 2.0,  7.0};
  for (double a : values) {
    for (int k = 0; k < 3; ++k) {
      Vector3d s(1.3, 0.7, 0.45);
      s(k) = a;
      const double h = 1e-6;
      Vector3d sp = s, sm = s;
      sp(k) += h;
      sm(k) -= h;
      const double fd = (m.energy(sp) - m.energy(sm)) / (2.0 * h);
      const double P = m.principal_stress(s)(k);
      const double tol = 1e-8 * std::abs(P) + 1e-9 * m.energy(s) + 1e-9 * kS0;
      EXPECT_NEAR(P, fd, tol) << "s_" << k << " = " << a;
    }
  }
}

// The continuation keeps penalizing compression: g' < 0 below s = 1 (also for s <= 0), > 0
// above; g' is increasing (g convex) and g >= 0 with g = 0 only at s = 1. Scanned on a fine grid
// of [-20, 20] that puts points within 1e-3 of s_c, 0 and 1.
TEST(XuMaterial, ContinuationIsRestoringAndConvex)
{
  double prev_slope = -std::numeric_limits<double>::infinity();
  for (int i = -20000; i <= 20000; ++i) {
    const double s = 1e-3 * i + 1e-4;    // avoids s = 1 exactly
    const double g = XuMaterial::stretch_energy(s), dg = XuMaterial::stretch_slope(s);
    ASSERT_TRUE(std::isfinite(g) && std::isfinite(dg)) << s;
    EXPECT_GT(g, 0.0) << s;
    if (s < 1.0) {
      EXPECT_LT(dg, 0.0) << s;
    } else {
      EXPECT_GT(dg, 0.0) << s;
    }
    EXPECT_GT(dg, prev_slope) << s;
    prev_slope = dg;
    if (HasFailure()) return;
  }
  // below s_c the slope is at most g'(s_c) < 0: the pull towards s = 1 never weakens
  for (double s : {0.29, 0.0, -0.5, -1.0, -1e3})
    EXPECT_LE(XuMaterial::stretch_slope(s), g1_def(kXuThreshold)) << s;
  // collapse and inversion of one direction, F = diag(1, 1, t): Phat_3 < 0 pushes t up
  const XuMaterial m(kS0);
  for (double t : {0.2, 0.0, -0.2, -1.0, -5.0})
    EXPECT_LT(m.principal_stress(Vector3d(1.0, 1.0, t))(2), 0.0) << t;
}

// c_k = s0 s_k^2 / 3 >= 0 at every state (continuous across s_c), and the explicit part is
// s0/3 h'(s_k): -s0/3 s_k^-3 above s_c.
TEST(XuMaterial, ImplicitCoefficient)
{
  const XuMaterial m(kS0);
  std::mt19937_64 rng(1709u);
  for (int i = 0; i < 500; ++i) {
    const Vector3d s(PeriSISSMTest::uniform(rng, -3.0, 3.0), PeriSISSMTest::uniform(rng, -3.0, 3.0),
                     PeriSISSMTest::uniform(rng, -3.0, 3.0));
    const PeriSISSM::PrincipalSplit sp = m.split(s);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(sp.c(k), 0.0);
      EXPECT_NEAR(sp.c(k), kS0 * s(k) * s(k) / 3.0, 1e-15 * kS0 * s(k) * s(k));
      if (s(k) >= kXuThreshold) {
        EXPECT_NEAR(sp.phat_minus(k), -kS0 / 3.0 * std::pow(s(k), -3),
                    1e-13 * kS0 * (std::pow(s(k), 3) + std::pow(s(k), -3)));
      }
    }
  }
  EXPECT_EQ(m.implicit_coefficient(Vector3d::Zero()), Vector3d::Zero());
}

// Small strain: the tangent dPhat_k/ds_l at rest is 2 s0 delta_kl, the linear model's with
// mu = s0, lambda = 0 (E = 2 s0, nu = 0): Phat agrees with it to O(e^2) relative to s0 e.
TEST(XuMaterial, SmallStrainIsLinearWithMuS0LambdaZero)
{
  const XuMaterial m(kS0);
  const PeriSISSM::LinearMaterial lin(kS0, 0.0);
  std::mt19937_64 rng(1721u);
  for (double e : {1e-3, 1e-5, 1e-7}) {
    for (int i = 0; i < 50; ++i) {
      const Vector3d dir = PeriSISSMTest::gaussian_matrix(rng).col(0).normalized();
      const Vector3d s = Vector3d::Ones() + e * dir;
      const Vector3d d = m.principal_stress(s) - lin.principal_stress(s);
      // Phat_k = s0/3 g'(1 + e_k) = 2 s0 e_k + 5 s0 e_k^2 + ...: remainder <= 6 s0 e^2
      EXPECT_LE(d.cwiseAbs().maxCoeff(), 6.0 * kS0 * e * e + 1e-12 * kS0 * e) << "e = " << e;
      EXPECT_NEAR(m.energy(s), lin.energy(s), 4.0 * kS0 * e * e * e + 1e-14 * lin.energy(s));
    }
  }
}

// Finite for every finite s: collapsed, inverted, tiny and huge singular values.
TEST(XuMaterial, FiniteEverywhere)
{
  const XuMaterial m(kS0);
  const std::vector<double> values = {0.0, -0.0, 1e-300, -1e-300, 1e-8, -1e-8,
                                      0.3, -0.3, 1e8,    -1e8,    1e50, -1e50};
  for (double a : values) {
    for (double b : values) {
      const Vector3d s(a, b, 1.0);
      const PeriSISSM::PrincipalSplit sp = m.split(s);
      EXPECT_TRUE(std::isfinite(m.energy(s))) << s.transpose();
      EXPECT_TRUE(sp.phat.allFinite() && sp.c.allFinite() && sp.phat_minus.allFinite())
          << s.transpose();
      EXPECT_GE(sp.c.minCoeff(), 0.0);
    }
  }
}

}    // namespace
