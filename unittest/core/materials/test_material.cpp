// Tests common to every material model, over >= 1000 seeded random F per model and parameter
// set: P = dW/dF, the implicit/explicit split, isotropy, the reference state, finiteness.

#include "linalg/signed_svd.h"
#include "materials/material.h"
#include "peri/particle.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSM::Material;
using PeriSISSMTest::MaterialCase;
using PeriSISSMTest::max_abs;

constexpr unsigned kSeed = 1234567u;

TEST(MaterialFactory, KnownNames)
{
  for (const std::string &name : PeriSISSM::material_names()) {
    const auto m = PeriSISSM::make_material(name, 2.0, 3.0);
    ASSERT_NE(m, nullptr) << name;
    EXPECT_EQ(name, m->name());
    EXPECT_EQ(m->mu(), 2.0);
    // xu has the one parameter s0 = mu and lambda = 0, whatever lambda the factory was given
    EXPECT_EQ(m->lambda(), name == "xu" ? 0.0 : 3.0);
  }
  EXPECT_EQ(PeriSISSM::material_names().size(), 4u);
  EXPECT_EQ(PeriSISSM::material_names_joined(), "linear, stvk, neohookean, xu");
}

TEST(MaterialFactory, UnknownNameGivesNull)
{
  EXPECT_EQ(PeriSISSM::make_material("neohooken", 1.0, 1.0), nullptr);
  EXPECT_EQ(PeriSISSM::make_material("", 1.0, 1.0), nullptr);
  EXPECT_EQ(PeriSISSM::make_material("Linear", 1.0, 1.0), nullptr);
}

TEST(MaterialFactory, LameFromBulkShear)
{
  const PeriSISSM::LameParameters p = PeriSISSM::lame_from_bulk_shear(3.0, 1.5);
  EXPECT_DOUBLE_EQ(p.mu, 1.5);
  EXPECT_DOUBLE_EQ(p.lambda, 2.0);
  EXPECT_TRUE(PeriSISSM::lame_parameters_admissible(1.0, -0.6));     // nu < 0
  EXPECT_FALSE(PeriSISSM::lame_parameters_admissible(1.0, -0.7));    // K < 0
  EXPECT_FALSE(PeriSISSM::lame_parameters_admissible(0.0, 1.0));     // G = 0
  EXPECT_FALSE(PeriSISSM::lame_parameters_admissible(1.0, std::nan("")));
}

// Parameterized over (model name, material parameter set).
class MaterialTest : public ::testing::TestWithParam<std::tuple<std::string, MaterialCase>> {
 protected:
  void SetUp() override
  {
    const MaterialCase &c = std::get<1>(GetParam());
    material_ = PeriSISSM::make_material(std::get<0>(GetParam()), c.mu, c.lambda);
    ASSERT_NE(material_, nullptr);
    modulus_ = std::abs(c.mu) + std::abs(c.lambda);
  }
  std::unique_ptr<Material> material_;
  double modulus_ = 0.0;    // stress scale mu + |lambda|
};

// P = dW/dF by central differences, h = 1e-6 |F|_F (floor 1e-9).
// Error budget of a central difference: truncation h^2/6 |W'''| ~ 1e-12 relative to P (W is a
// polynomial or log of F of moderate degree on the scale |F|), plus round-off
// ~ eps |W terms| / h with |W terms| <~ modulus (1 + |F|^2)^2 (the largest term that cancels in
// W, e.g. mu/2 |F|^2 near F = I), i.e. ~2e-10 modulus (1 + |F|^2)^2 / |F|. So require
//   max|P_fd - P| <= 1e-6 max|P| + 1e-8 modulus (1 + |F|^2)^2 / max(|F|, 1e-3):
// a relative 1e-6 on the stress, and a floor 50x above the round-off estimate that only matters
// where P itself is ~1e-3 modulus or less (near-identity F). A sign or factor error in any term
// of Phat is an O(1) relative error.
TEST_P(MaterialTest, StressIsEnergyGradient)
{
  const auto W = [this](const Matrix3d &F) {
    return PeriSISSMTest::energy_of_F(*material_, F);
  };
  double worst = 0.0;
  for (const auto &sample : PeriSISSMTest::random_samples(kSeed)) {
    const Matrix3d &F = sample.F;
    const double normF = F.norm();
    const double h = 1e-6 * std::max(normF, 1e-3);
    const Matrix3d P = PeriSISSM::first_piola(*material_, F);
    const Matrix3d Pfd = PeriSISSMTest::fd_gradient(W, F, h);
    const double floor = 1e-8 * modulus_ * std::pow(1.0 + normF * normF, 2) / std::max(normF, 1e-3);
    const double tol = 1e-6 * max_abs(P) + floor;
    const double err = max_abs(P - Pfd);
    worst = std::max(worst, err / tol);
    ASSERT_LE(err, tol) << PeriSISSMTest::family_name(sample.family) << "\nF =\n"
                        << F << "\nP =\n"
                        << P << "\nP_fd =\n"
                        << Pfd;
  }
  RecordProperty("worst_error_over_tolerance", std::to_string(worst));
}

// Phat^+ + Phat^- = Phat to round-off and c >= 0, finite.
TEST_P(MaterialTest, SplitAddsUpAndIsNonNegative)
{
  for (const auto &sample : PeriSISSMTest::random_samples(kSeed + 1)) {
    const Vector3d s = PeriSISSM::signed_svd(sample.F).s;
    const PeriSISSM::PrincipalSplit sp = material_->split(s);
    ASSERT_TRUE(sp.c.allFinite() && sp.phat.allFinite() && sp.phat_minus.allFinite());
    EXPECT_GE(sp.c.minCoeff(), 0.0);
    const Vector3d plus = sp.c.cwiseProduct(s);
    const double scale = plus.cwiseAbs().maxCoeff() + sp.phat.cwiseAbs().maxCoeff();
    EXPECT_LE((plus + sp.phat_minus - sp.phat).cwiseAbs().maxCoeff(), 4e-16 * scale);
    EXPECT_EQ(sp.phat, material_->principal_stress(s));
    EXPECT_EQ(sp.c, material_->implicit_coefficient(s));
    if (HasFailure()) return;
  }
}

// W(R F) = W(F), W(F R) = W(F), P(R F) = R P(F), P(F R) = P(F) R for random rotations R.
TEST_P(MaterialTest, Isotropy)
{
  std::mt19937_64 rng(kSeed + 2);
  for (const auto &sample : PeriSISSMTest::random_samples(kSeed + 3)) {
    const Matrix3d &F = sample.F;
    const Matrix3d R = PeriSISSMTest::random_rotation(rng);
    const double W = PeriSISSMTest::energy_of_F(*material_, F);
    const Matrix3d P = PeriSISSM::first_piola(*material_, F);
    const double n2 = F.squaredNorm();
    const double wtol = 1e-12 * (std::abs(W) + modulus_ * (1.0 + n2) * (1.0 + n2));
    const double ptol = 1e-11 * (max_abs(P) + modulus_ * (1.0 + n2));
    EXPECT_NEAR(PeriSISSMTest::energy_of_F(*material_, R * F), W, wtol);
    EXPECT_NEAR(PeriSISSMTest::energy_of_F(*material_, F * R), W, wtol);
    EXPECT_LE(max_abs(PeriSISSM::first_piola(*material_, R * F) - R * P), ptol);
    EXPECT_LE(max_abs(PeriSISSM::first_piola(*material_, F * R) - P * R), ptol);
    if (HasFailure()) {
      ADD_FAILURE() << PeriSISSMTest::family_name(sample.family) << "\nF =\n" << F;
      return;
    }
  }
}

// The undeformed state (and any rotation of it) is stress and energy free.
TEST_P(MaterialTest, ReferenceStateIsStressFree)
{
  EXPECT_EQ(material_->energy(Vector3d::Ones()), 0.0);
  EXPECT_EQ(material_->principal_stress(Vector3d::Ones()), Vector3d::Zero());
  EXPECT_EQ(PeriSISSM::first_piola(*material_, Matrix3d::Identity()), Matrix3d::Zero());
  std::mt19937_64 rng(kSeed + 4);
  for (int i = 0; i < 100; ++i) {
    const Matrix3d R = PeriSISSMTest::random_rotation(rng);
    EXPECT_LE(std::abs(PeriSISSMTest::energy_of_F(*material_, R)), 1e-14 * modulus_);
    EXPECT_LE(max_abs(PeriSISSM::first_piola(*material_, R)), 1e-14 * modulus_);
  }
}

// W, P, c and the per-particle quantities are finite for degenerate and extreme F.
TEST_P(MaterialTest, FiniteForDegenerateAndExtremeF)
{
  std::mt19937_64 rng(kSeed + 5);
  std::vector<Matrix3d> Fs = {Matrix3d::Zero(),
                              -Matrix3d::Identity(),
                              Vector3d(1, 1, -1).asDiagonal(),
                              Vector3d(1, 1, 0).asDiagonal(),
                              Vector3d(1, 0, 0).asDiagonal(),
                              Vector3d(1e8, 1, 1e-8).asDiagonal(),
                              Vector3d(1e-8, 1e-8, -1e-8).asDiagonal()};
  for (int i = 0; i < 50; ++i) {
    const Vector3d a = PeriSISSMTest::gaussian_matrix(rng).col(0);
    const Vector3d b = PeriSISSMTest::gaussian_matrix(rng).col(0);
    const Matrix3d R = PeriSISSMTest::random_rotation(rng);
    const Matrix3d G = PeriSISSMTest::gaussian_matrix(rng);
    Fs.push_back(a * b.transpose());    // rank 1
    Fs.push_back(1e8 * R);              // huge
    Fs.push_back(1e-8 * R);             // tiny
    Fs.push_back(1e8 * G);              // huge, either det sign
    Fs.push_back(1e-8 * G);             // tiny, either det sign
    Fs.push_back(-1e8 * R);             // huge inverted
    Fs.push_back(R * Vector3d(1e-8, 1e-8, -1.0).asDiagonal());
  }
  for (const Matrix3d &F : Fs) {
    PeriSISSM::ParticleStress ps;
    PeriSISSM::particle_stress(*material_, F, ps, true);
    const PeriSISSM::PrincipalSplit sp = material_->split(ps.svd.s);
    EXPECT_TRUE(std::isfinite(ps.W)) << F;
    EXPECT_TRUE(ps.P.allFinite() && PeriSISSM::implicit_part(ps).allFinite() &&
                PeriSISSM::implicit_direction(ps).allFinite())
        << F;
    EXPECT_TRUE(sp.c.allFinite() && sp.phat_minus.allFinite()) << F;
    EXPECT_GE(sp.c.minCoeff(), 0.0);
    if (HasFailure()) return;
  }
}

std::string case_name(const ::testing::TestParamInfo<MaterialTest::ParamType> &info)
{
  return std::get<0>(info.param) + "_" + std::get<1>(info.param).label;
}

INSTANTIATE_TEST_SUITE_P(AllModels, MaterialTest,
                         ::testing::Combine(::testing::ValuesIn(PeriSISSM::material_names()),
                                            ::testing::ValuesIn(PeriSISSMTest::material_cases())),
                         case_name);

}    // namespace
