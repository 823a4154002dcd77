// Corotated linear model: energy against its matrix form, the implicit coefficient.

#include "linalg/signed_svd.h"
#include "materials/material_linear.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// For F = R S (R rotation, S symmetric positive definite): W = mu |S - I|^2 + lambda/2 tr(S - I)^2.
TEST(LinearMaterial, EnergyMatchesPolarForm)
{
  const PeriSISSM::LinearMaterial m(1.3, 0.7);
  std::mt19937_64 rng(31u);
  for (int i = 0; i < 500; ++i) {
    const Matrix3d G = PeriSISSMTest::gaussian_matrix(rng);
    const Matrix3d S = Matrix3d::Identity() + 0.1 * (G + G.transpose());
    const Matrix3d F = PeriSISSMTest::random_rotation(rng) * S;
    const Matrix3d E = S - Matrix3d::Identity();
    const double W = 1.3 * E.squaredNorm() + 0.35 * E.trace() * E.trace();
    EXPECT_NEAR(PeriSISSMTest::energy_of_F(m, F), W, 1e-13 * (1.0 + W));
  }
}

// c_k = 2 mu + lambda for every state (also lambda < 0), equal to dPhat_k/ds_k, so the explicit
// part Phat_k - c_k s_k does not depend on s_k.
TEST(LinearMaterial, ImplicitCoefficientIsPWaveModulus)
{
  std::mt19937_64 rng(37u);
  for (const auto &c : PeriSISSMTest::material_cases()) {
    const PeriSISSM::LinearMaterial m(c.mu, c.lambda);
    for (int i = 0; i < 100; ++i) {
      const Vector3d s(PeriSISSMTest::uniform(rng, 0.1, 3), PeriSISSMTest::uniform(rng, 0.1, 3),
                       PeriSISSMTest::uniform(rng, -1, 1));
      const PeriSISSM::PrincipalSplit sp = m.split(s);
      EXPECT_EQ(sp.c, Vector3d::Constant(2 * c.mu + c.lambda));
      for (int k = 0; k < 3; ++k) {
        Vector3d sp1 = s;
        sp1(k) += 0.25;
        const PeriSISSM::PrincipalSplit sq = m.split(sp1);
        const double tol = 1e-12 * (c.mu + std::abs(c.lambda));
        EXPECT_NEAR(sq.phat(k) - sp.phat(k), 0.25 * (2 * c.mu + c.lambda), tol);
        EXPECT_NEAR(sq.phat_minus(k), sp.phat_minus(k), tol);
      }
    }
  }
}

}    // namespace
