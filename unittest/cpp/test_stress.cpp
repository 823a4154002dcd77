// Tests of first_piola() and particle_stress(): consistency of the per-particle quantities and
// the small-strain limit shared by all models.

#include "material.h"
#include "stress.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSMTest::max_abs;

TEST(ParticleStress, ConsistentWithFirstPiolaAndSplit)
{
  for (const std::string& name : PeriSISSM::material_names()) {
    for (const auto& c : PeriSISSMTest::material_cases()) {
      SCOPED_TRACE(name + " " + c.label);
      const auto m = PeriSISSM::make_material(name, c.mu, c.lambda);
      for (const auto& sample : PeriSISSMTest::random_samples(61u, 30)) {
        const Matrix3d& F = sample.F;
        PeriSISSM::ParticleStress ps;
        PeriSISSM::particle_stress(*m, F, ps);
        const PeriSISSM::PrincipalSplit sp = m->split(ps.svd.s);
        const double pscale = max_abs(ps.P) + max_abs(ps.P_implicit) + 1e-300;
        EXPECT_EQ(ps.P, PeriSISSM::first_piola(*m, F));
        EXPECT_EQ(ps.W, PeriSISSMTest::energy_of_F(*m, F));
        EXPECT_NEAR(ps.J, F.determinant(), 1e-12 * std::pow(F.norm(), 3));
        // Explicit part: P - P^+ = U diag(Phat^-) V^T.
        const Matrix3d Pminus = ps.svd.U * sp.phat_minus.asDiagonal() * ps.svd.V.transpose();
        EXPECT_LE(max_abs(ps.P - ps.P_implicit - Pminus), 1e-13 * pscale);
        // Stiffness direction: symmetric, PSD, and D F = P^+.
        EXPECT_EQ(ps.stiffness, ps.stiffness.transpose());
        const double dscale = sp.c.maxCoeff() + 1e-300;
        const Vector3d ev =
            Eigen::SelfAdjointEigenSolver<Matrix3d>(ps.stiffness, Eigen::EigenvaluesOnly)
                .eigenvalues();
        EXPECT_GE(ev.minCoeff(), -1e-14 * dscale);
        EXPECT_LE(max_abs(ps.stiffness * F - ps.P_implicit),
                  1e-13 * (max_abs(ps.P_implicit) + dscale * max_abs(F)));
        if (HasFailure()) return;
      }
    }
  }
}

// Corotated linear: c_k = 2 mu + lambda, so the stiffness direction is isotropic (math.md 3).
TEST(ParticleStress, LinearStiffnessIsIsotropic)
{
  const auto m = PeriSISSM::make_material("linear", 1.0, 1.5);
  std::mt19937_64 rng(67u);
  for (int i = 0; i < 100; ++i) {
    PeriSISSM::ParticleStress ps;
    PeriSISSM::particle_stress(*m, PeriSISSMTest::gaussian_matrix(rng), ps);
    EXPECT_LE(max_abs(ps.stiffness - 3.5 * Matrix3d::Identity()), 1e-14 * 3.5);
  }
}

// Small strain, F = I + e G: every model's P is the linear elastic
// sigma(e G) = 2 mu sym(e G) + lambda tr(e G) I up to O(e^2), so the relative differences
// between models and to sigma are O(e): they shrink ~10x when e does.
TEST(FirstPiola, SmallStrainLimitIsLinearElasticity)
{
  const auto& names = PeriSISSM::material_names();
  std::mt19937_64 rng(71u);
  for (const auto& c : PeriSISSMTest::material_cases()) {
    std::vector<std::unique_ptr<PeriSISSM::Material>> models;
    for (const std::string& name : names)
      models.push_back(PeriSISSM::make_material(name, c.mu, c.lambda));
    for (int trial = 0; trial < 20; ++trial) {
      const Matrix3d G = PeriSISSMTest::gaussian_matrix(rng);
      double rel_lin[2][3];
      double rel_pair[2][3];
      int col = 0;
      for (double e : {1e-4, 1e-5}) {
        const Matrix3d F = Matrix3d::Identity() + e * G;
        const Matrix3d eps = 0.5 * e * (G + G.transpose());
        const Matrix3d sigma = 2 * c.mu * eps + c.lambda * eps.trace() * Matrix3d::Identity();
        Matrix3d P[3];
        for (int k = 0; k < 3; ++k) P[k] = PeriSISSM::first_piola(*models[k], F);
        for (int k = 0; k < 3; ++k) {
          rel_lin[col][k] = (P[k] - sigma).norm() / sigma.norm();
          rel_pair[col][k] = (P[k] - P[(k + 1) % 3]).norm() / P[k].norm();
        }
        ++col;
      }
      for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(c.label + " " + names[k] + " vs linear elasticity / vs " + names[(k + 1) % 3]);
        // O(e): at e = 1e-4 below 100 e, and 5x to 20x smaller at e = 1e-5.
        EXPECT_LT(rel_lin[0][k], 1e-2);
        EXPECT_LT(rel_pair[0][k], 1e-2);
        EXPECT_GT(rel_lin[0][k] / rel_lin[1][k], 5.0);
        EXPECT_LT(rel_lin[0][k] / rel_lin[1][k], 20.0);
        EXPECT_GT(rel_pair[0][k] / rel_pair[1][k], 5.0);
        EXPECT_LT(rel_pair[0][k] / rel_pair[1][k], 20.0);
      }
      if (HasFailure()) return;
    }
  }
}

}  // namespace
