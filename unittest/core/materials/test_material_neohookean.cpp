// Neo-Hookean: energy against its matrix form, and the continuation below J0 (C2 at J0,
// finite, restoring).

#include "linalg/signed_svd.h"
#include "materials/material_neohookean.h"
#include "peri/particle.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSM::NeoHookeanMaterial;

// W = mu/2 (tr F^T F - 3) - mu ln J + lambda/2 (ln J)^2 wherever J >= J0.
TEST(NeoHookeanMaterial, EnergyMatchesMatrixFormAboveThreshold)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    const NeoHookeanMaterial m(c.mu, c.lambda);
    for (const auto &sample : PeriSISSMTest::random_samples(53u, 40)) {
      const Matrix3d &F = sample.F;
      const double J = F.determinant();
      if (J < m.continuation_threshold()) continue;
      const double W = 0.5 * c.mu * (F.squaredNorm() - 3.0) - c.mu * std::log(J) +
          0.5 * c.lambda * std::log(J) * std::log(J);
      const double scale = (c.mu + std::abs(c.lambda)) * (1.0 + F.squaredNorm());
      EXPECT_NEAR(PeriSISSMTest::energy_of_F(m, F), W, 1e-13 * scale);
    }
  }
}

// Near rest W is O(e^2) for F = I + e G while its terms mu/2 (|s|^2 - 3) and -mu ln J are O(e)
// each: summed as written they cancel and leave an absolute error of ~eps mu, a relative error
// of ~eps / e^2 (~1e-4 at e = 1e-6, ~1 at e = 1e-8). W must be accurate to round-off relative
// to itself (material_neohookean.cpp).
//
// Reference: for principal strains eps_k (s_k = 1 + eps_k), expanding ln(1 + eps) gives
//   W = mu |E|^2 + lambda/2 tr(E)^2  -  mu/3 tr(E^3) - lambda/2 tr(E) |E|^2  +  O(e^4)
// with E = diag(eps) (or any symmetric E with those eigenvalues): the small-strain quadratic
// form plus its cubic correction, whose relative size ~2.5 e for unit |E|/e exceeds 1e-6 at
// e = 1e-6 and must therefore be in the reference. The remainder is ~6 e^2 relative (measured).
double neohookean_reference_near_rest(double mu, double lambda, const Matrix3d &E)
{
  const double tr = E.trace(), n2 = E.squaredNorm(), tr3 = (E * E * E).trace();
  return mu * n2 + 0.5 * lambda * tr * tr - mu / 3.0 * tr3 - 0.5 * lambda * tr * n2;
}

// W(s) itself, singular values given: round-off relative to W down to e = 1e-10 (the
// reference's remainder is 6e-20 there).
TEST(NeoHookeanMaterial, EnergyAccurateNearRestOnSingularValues)
{
  std::mt19937_64 rng(89u);
  for (const auto &c : PeriSISSMTest::material_cases()) {
    SCOPED_TRACE(c.label);
    const NeoHookeanMaterial m(c.mu, c.lambda);
    for (double e : {1e-10, 1e-8, 1e-6}) {
      for (int trial = 0; trial < 40; ++trial) {
        const Vector3d dir = PeriSISSMTest::gaussian_matrix(rng).col(0).normalized();
        const Vector3d s = Vector3d::Ones() + e * dir;
        const Matrix3d E = (s - Vector3d::Ones()).asDiagonal();    // exact: s_k - 1
        const double ref = neohookean_reference_near_rest(c.mu, c.lambda, E);
        EXPECT_NEAR(m.energy(s), ref, (1e-14 + 10.0 * e * e) * ref)
            << "e = " << e << ", trial " << trial;
      }
    }
    // At rest W = 0 exactly.
    EXPECT_EQ(m.energy(Vector3d(1, 1, 1)), 0.0);
  }
}

// Through the signed SVD, F = R (I + e S) with S symmetric, |S| = 1, R a rotation: the SVD
// gives s_k to a few 1e-15 absolute, i.e. ~1e-14 / e relative in eps_k and in W; tolerance
// 5e-14 / e (+ the reference's remainder). At e = 1e-6 that is 5e-8; the unfixed form is off by
// ~1e-4 there. Pure shears S ~ diag(1, -1, 0) have tr E = tr E^3 = 0: W is then the quadratic
// form mu |sym eG|^2 + lambda/2 tr(eG)^2 itself to O(e^4), required to 1e-6 relative.
TEST(NeoHookeanMaterial, EnergyAccurateNearRest)
{
  std::mt19937_64 rng(97u);
  for (const auto &c : PeriSISSMTest::material_cases()) {
    SCOPED_TRACE(c.label);
    const NeoHookeanMaterial m(c.mu, c.lambda);
    for (double e : {1e-4, 1e-6, 1e-8}) {
      const double tol = 5e-14 / e + 10.0 * e * e;
      for (int trial = 0; trial < 40; ++trial) {
        const Matrix3d G = PeriSISSMTest::gaussian_matrix(rng);
        const Matrix3d E = e * (G + G.transpose()).normalized();
        const Matrix3d F = PeriSISSMTest::random_rotation(rng) * (Matrix3d::Identity() + E);
        const double ref = neohookean_reference_near_rest(c.mu, c.lambda, E);
        EXPECT_NEAR(PeriSISSMTest::energy_of_F(m, F), ref, tol * ref)
            << "e = " << e << ", trial " << trial;
      }
    }
    const double e = 1e-6;
    for (int trial = 0; trial < 40; ++trial) {
      const Matrix3d Q = PeriSISSMTest::random_rotation(rng);
      const Matrix3d eG = e * Q * Vector3d(1.0, -1.0, 0.0).asDiagonal() * Q.transpose();
      const double quad = c.mu * eG.squaredNorm() + 0.5 * c.lambda * eG.trace() * eG.trace();
      const Matrix3d F = PeriSISSMTest::random_rotation(rng) * (Matrix3d::Identity() + eG);
      EXPECT_NEAR(PeriSISSMTest::energy_of_F(m, F), quad, 1e-6 * quad) << "trial " << trial;
    }
  }
}

// The accurate form switches its evaluation of x - ln(1 + x) at |x| = 1/4: W stays equal to
// the defining form there (where that form has no cancellation to speak of).
TEST(NeoHookeanMaterial, EnergyContinuousAtSeriesSwitch)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    SCOPED_TRACE(c.label);
    const NeoHookeanMaterial m(c.mu, c.lambda);
    for (double x0 : {0.25, -0.25}) {
      for (double x : {x0 * (1.0 - 1e-12), x0, x0 * (1.0 + 1e-12)}) {
        const Vector3d s(1.0 + x, 1.0, 1.0);
        const double lnj = std::log1p(x);
        const double W = c.mu * (0.5 * x * x + x - lnj) + 0.5 * c.lambda * lnj * lnj;
        EXPECT_NEAR(m.energy(s), W, 1e-14 * (c.mu + std::abs(c.lambda))) << "x = " << x;
      }
    }
  }
}

// c_k is the whole tangent dPhat_k/ds_k where the volumetric curvature is positive: the
// P-wave modulus 2 mu + lambda at rest (what the SISSM block needs to contract), and a central
// difference of Phat_k in s_k elsewhere (Phat_k is quadratic-free in s_k only through g, so the
// difference is accurate to ~1e-7 relative with step 1e-6).
TEST(NeoHookeanMaterial, ImplicitCoefficientIsTheTangentWhereCurvatureIsPositive)
{
  const NeoHookeanMaterial m(2.5, 1.0);
  const Vector3d rest = m.implicit_coefficient(Vector3d(1, 1, 1));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rest(k), 2 * 2.5 + 1.0, 1e-14);
  for (const Vector3d &s : {Vector3d(1.2, 0.9, 0.8), Vector3d(2.0, 1.5, 0.3),
                            Vector3d(0.6, 0.5, 0.4), Vector3d(0.5, 0.4, 0.2)}) {
    const Vector3d c = m.implicit_coefficient(s);
    for (int k = 0; k < 3; ++k) {
      Vector3d sp = s, sm = s;
      const double e = 1e-6;
      sp(k) += e;
      sm(k) -= e;
      const double slope = (m.principal_stress(sp)(k) - m.principal_stress(sm)(k)) / (2 * e);
      EXPECT_NEAR(c(k), slope, 1e-6 * std::abs(slope)) << "s = " << s.transpose();
    }
  }
  // finite and at least mu for degenerate and inverted states
  for (const Vector3d &s : {Vector3d(3, 2, -1), Vector3d(0, 0, 0), Vector3d(1e3, 1e3, 1e3)}) {
    const Vector3d c = m.implicit_coefficient(s);
    EXPECT_TRUE(c.allFinite());
    EXPECT_GE(c.minCoeff(), 2.5);
  }
}

// J0 = 0.1 for lambda >= 0; raised to exp(1 + mu/lambda) for lambda < 0 when that is larger,
// so that g''(J0) >= 0.
TEST(NeoHookeanContinuation, Threshold)
{
  EXPECT_EQ(NeoHookeanMaterial(1.0, 1.5).continuation_threshold(), PeriSISSM::kNeoHookeanJ0);
  EXPECT_EQ(NeoHookeanMaterial(1.0, 0.0).continuation_threshold(), PeriSISSM::kNeoHookeanJ0);
  EXPECT_EQ(NeoHookeanMaterial(1.0, -0.2).continuation_threshold(), PeriSISSM::kNeoHookeanJ0);
  EXPECT_DOUBLE_EQ(NeoHookeanMaterial(1.0, -0.375).continuation_threshold(),
                   std::exp(1.0 - 1.0 / 0.375));
  EXPECT_LT(NeoHookeanMaterial(1.0, -0.66).continuation_threshold(), std::exp(-0.5));
}

// W and P continuous across J0: compare J = J0 (1 - 1e-9) with J0 (1 + 1e-9), for uniform and
// for distorted shapes. A C0 jump would be O(modulus); the change over 2e-9 J0 is
// |dW/dJ| 2e-9 J0 <~ 1e-7 modulus. Also C1 and C2 of the volumetric term g at J0 by one-sided
// differences.
TEST(NeoHookeanContinuation, ContinuousAtThreshold)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    SCOPED_TRACE(c.label);
    const NeoHookeanMaterial m(c.mu, c.lambda);
    const double j0 = m.continuation_threshold();
    const double modulus = c.mu + std::abs(c.lambda);
    for (const Vector3d &shape : {Vector3d(1, 1, 1), Vector3d(2, 1, 0.5), Vector3d(3, 0.5, -1)}) {
      const double J0shape = shape.prod();
      Vector3d sm = shape, sp = shape;
      sm(2) *= j0 * (1.0 - 1e-9) / J0shape;
      sp(2) *= j0 * (1.0 + 1e-9) / J0shape;
      EXPECT_LT(sm.prod(), j0);
      EXPECT_GT(sp.prod(), j0);
      EXPECT_NEAR(m.energy(sm), m.energy(sp), 1e-6 * modulus);
      EXPECT_LE((m.principal_stress(sm) - m.principal_stress(sp)).cwiseAbs().maxCoeff(),
                1e-6 * modulus);
    }
    const double d = 1e-5 * j0;
    const double below = (m.volumetric_slope(j0 - d) - m.volumetric_slope(j0 - 2 * d)) / d;
    const double above = (m.volumetric_slope(j0 + 2 * d) - m.volumetric_slope(j0 + d)) / d;
    const double g2 = (c.mu + c.lambda * (1.0 - std::log(j0))) / (j0 * j0);
    EXPECT_NEAR(below, std::max(g2, 0.0), 1e-3 * modulus / (j0 * j0));
    EXPECT_NEAR(above, g2, 1e-3 * modulus / (j0 * j0));
    EXPECT_NEAR(m.volumetric_slope(j0 - d), m.volumetric_slope(j0 + d), 1e-3 * modulus / j0);
    // g' is the derivative of g on both sides.
    for (double J : {j0 * 0.5, j0 * 2.0, -1.0, 0.0}) {
      const double h = 1e-6;
      const double fd = (m.volumetric_energy(J + h) - m.volumetric_energy(J - h)) / (2 * h);
      EXPECT_NEAR(fd, m.volumetric_slope(J), 1e-6 * modulus / j0) << "J = " << J;
    }
  }
}

// The volumetric term alone pushes J up everywhere below J0 (g' < 0), for every material.
TEST(NeoHookeanContinuation, VolumetricTermRestoringBelowThreshold)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    const NeoHookeanMaterial m(c.mu, c.lambda);
    const double j0 = m.continuation_threshold();
    for (double J = j0 * (1 - 1e-9); J > -100.0; J -= 0.01 * (1.0 + std::abs(J)))
      EXPECT_LT(m.volumetric_slope(J), 0.0) << c.label << " J = " << J;
  }
}

// dW/dJ along a path F(t) with J(t): dW/dt = P : dF/dt, divided by dJ/dt.
double dW_dJ_uniform(const NeoHookeanMaterial &m, double t)
{
  const Matrix3d P = PeriSISSM::first_piola(m, t * Matrix3d::Identity());
  return P.trace() / (3.0 * t * t);
}

// Along uniform compression F = t I (lambda >= 0): dW/dJ < 0 for J = t^3 from J0 down to
// J0^3 = 1e-3, and for every uniformly inverted F (t < 0). Below J_c (<= 1e-3, ~1.25e-4 for
// lambda = 0) it cannot be: F = 0 is a local minimum of any g-only continuation
// (material_neohookean.h).
TEST(NeoHookeanContinuation, RestoringUnderUniformCompression)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    if (c.lambda < 0.0) continue;    // the model itself is not restoring here (header)
    const NeoHookeanMaterial m(c.mu, c.lambda);
    const double j0 = m.continuation_threshold();
    for (double J = j0 * (1 - 1e-9); J >= 1e-3; J *= 0.9)
      EXPECT_LT(dW_dJ_uniform(m, std::cbrt(J)), 0.0) << c.label << " J = " << J;
    for (double t = -1e-3; t > -10.0; t *= 1.1)
      EXPECT_LT(dW_dJ_uniform(m, t), 0.0) << c.label << " t = " << t;
  }
}

// Uniaxial collapse and inversion F = diag(1, 1, t), t < J0: dW/dJ = P_33 < 0 (pushes t up), for
// every material including lambda < 0.
TEST(NeoHookeanContinuation, RestoringUnderUniaxialCollapseAndInversion)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    const NeoHookeanMaterial m(c.mu, c.lambda);
    const double j0 = m.continuation_threshold();
    for (double t = j0 * (1 - 1e-9); t > -100.0; t -= 0.01 * (0.1 + std::abs(t))) {
      const Matrix3d P = PeriSISSM::first_piola(m, Vector3d(1, 1, t).asDiagonal());
      EXPECT_LT(P(2, 2), 0.0) << c.label << " t = " << t;
    }
  }
}

}    // namespace
