// St. Venant-Kirchhoff: energy against its matrix form, the implicit coefficient.

#include "linalg/signed_svd.h"
#include "materials/material_stvk.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// W = mu E:E + lambda/2 tr(E)^2 with E = (F^T F - I)/2, for any F (inverted included).
TEST(StVKMaterial, EnergyMatchesGreenLagrangeForm)
{
  for (const auto &c : PeriSISSMTest::material_cases()) {
    const PeriSISSM::StVKMaterial m(c.mu, c.lambda);
    for (const auto &sample : PeriSISSMTest::random_samples(43u, 20)) {
      const Matrix3d &F = sample.F;
      const Matrix3d E = 0.5 * (F.transpose() * F - Matrix3d::Identity());
      const double W = c.mu * E.squaredNorm() + 0.5 * c.lambda * E.trace() * E.trace();
      const double scale = (c.mu + std::abs(c.lambda)) * (1.0 + std::pow(F.squaredNorm(), 2));
      EXPECT_NEAR(PeriSISSMTest::energy_of_F(m, F), W, 1e-13 * scale);
    }
  }
}

// c_k = mu s_k^2 + max(lambda, 0)/2 sum_l s_l^2, and the explicit part is
// -(mu + 3 lambda/2) s_k + min(lambda, 0)/2 s_k sum_l s_l^2.
TEST(StVKMaterial, ImplicitCoefficientFormula)
{
  std::mt19937_64 rng(47u);
  for (const auto &c : PeriSISSMTest::material_cases()) {
    const PeriSISSM::StVKMaterial m(c.mu, c.lambda);
    const double scale = c.mu + std::abs(c.lambda);
    for (int i = 0; i < 200; ++i) {
      const Vector3d s(PeriSISSMTest::uniform(rng, 0.1, 3), PeriSISSMTest::uniform(rng, 0.1, 3),
                       PeriSISSMTest::uniform(rng, -1, 1));
      const double q = s.squaredNorm();
      const PeriSISSM::PrincipalSplit sp = m.split(s);
      for (int k = 0; k < 3; ++k) {
        const double ck = c.mu * s(k) * s(k) + 0.5 * std::max(c.lambda, 0.0) * q;
        const double mk =
            -(c.mu + 1.5 * c.lambda) * s(k) + 0.5 * std::min(c.lambda, 0.0) * s(k) * q;
        EXPECT_NEAR(sp.c(k), ck, 1e-14 * scale * (1 + q));
        EXPECT_NEAR(sp.phat_minus(k), mk, 1e-13 * scale * (1 + q) * (1 + q));
      }
    }
  }
}

}    // namespace
