// Tests of signed_svd(): reconstruction, orthonormality, proper rotations, ordering and the
// sign convention, on random F of every family and on the special cases that break naive code.

#include "linalg/signed_svd.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSM::SignedSVD;
using PeriSISSM::signed_svd;
using PeriSISSMTest::max_abs;

// Tolerances: Jacobi SVD reconstructs to a few eps relative to |F| and accumulates U, V from
// O(10) plane rotations, so 1e-12 leaves two orders of magnitude of head room.
constexpr double kTol = 1e-12;

// Every property of the contract, for one F. label names the case in failure messages.
void check_signed_svd(const Matrix3d& F, const std::string& label)
{
  SCOPED_TRACE(label);
  const SignedSVD d = signed_svd(F);
  ASSERT_TRUE(d.U.allFinite() && d.V.allFinite() && d.s.allFinite());

  const Matrix3d I = Matrix3d::Identity();
  EXPECT_LE(max_abs(d.U.transpose() * d.U - I), kTol);
  EXPECT_LE(max_abs(d.V.transpose() * d.V - I), kTol);
  EXPECT_NEAR(d.U.determinant(), 1.0, kTol);
  EXPECT_NEAR(d.V.determinant(), 1.0, kTol);

  const Matrix3d R = d.U * d.s.asDiagonal() * d.V.transpose();
  EXPECT_LE(max_abs(R - F), kTol * max_abs(F)) << "F =\n" << F << "\nUSV^T =\n" << R;

  // Ordering by magnitude; only the last entry may be negative.
  EXPECT_GE(std::abs(d.s(0)), std::abs(d.s(1)));
  EXPECT_GE(std::abs(d.s(1)), std::abs(d.s(2)));
  EXPECT_GE(d.s(0), 0.0);
  EXPECT_GE(d.s(1), 0.0);

  // Sign convention: s_3 < 0 exactly when det F < 0. Checked where det F is not round-off,
  // i.e. |det F| above 1e-10 of the largest possible |det F| = s_1^3.
  const double detF = F.determinant();
  const double s1 = std::abs(d.s(0));
  if (std::abs(detF) > 1e-10 * s1 * s1 * s1) {
    EXPECT_EQ(d.s(2) < 0.0, detF < 0.0) << "det F = " << detF << " s = " << d.s.transpose();
    EXPECT_NEAR(d.s.prod(), detF, 1e-12 * s1 * s1 * s1);
  }
  EXPECT_FALSE(std::signbit(d.s(2)) && d.s(2) == 0.0) << "s_3 = -0";
}

TEST(SignedSVD, RandomFamilies)
{
  for (const auto& sample : PeriSISSMTest::random_samples(20240601u)) {
    check_signed_svd(sample.F, PeriSISSMTest::family_name(sample.family));
    if (HasFailure()) return;
  }
}

TEST(SignedSVD, ExtremeScales)
{
  std::mt19937_64 rng(7u);
  for (double scale : {1e-8, 1e8, 1e-150, 1e150}) {
    for (int i = 0; i < 200; ++i) {
      const Matrix3d F = scale * PeriSISSMTest::gaussian_matrix(rng);
      check_signed_svd(F, "scale " + std::to_string(scale));
      const SignedSVD d0 = signed_svd(F / scale);
      const SignedSVD d = signed_svd(F);
      EXPECT_LE((d.s / scale - d0.s).cwiseAbs().maxCoeff(), kTol * d0.s.cwiseAbs().maxCoeff());
      if (HasFailure()) return;
    }
  }
}

TEST(SignedSVD, Identity)
{
  const SignedSVD d = signed_svd(Matrix3d::Identity());
  EXPECT_EQ(d.s, Vector3d::Ones());
  check_signed_svd(Matrix3d::Identity(), "I");
}

TEST(SignedSVD, Zero)
{
  const SignedSVD d = signed_svd(Matrix3d::Zero());
  EXPECT_EQ(d.s, Vector3d::Zero());
  check_signed_svd(Matrix3d::Zero(), "0");
}

TEST(SignedSVD, MinusIdentityAndReflections)
{
  const SignedSVD d = signed_svd(-Matrix3d::Identity());
  EXPECT_LE((d.s - Vector3d(1, 1, -1)).cwiseAbs().maxCoeff(), kTol);
  check_signed_svd(-Matrix3d::Identity(), "-I");
  for (int k = 0; k < 3; ++k) {
    Matrix3d F = Matrix3d::Identity();
    F(k, k) = -1.0;
    const SignedSVD dk = signed_svd(F);
    EXPECT_LE((dk.s - Vector3d(1, 1, -1)).cwiseAbs().maxCoeff(), kTol);
    check_signed_svd(F, "reflection " + std::to_string(k));
  }
  // Permutation matrices: rotations (det +1) and reflections (det -1).
  Matrix3d P;
  P << 0, 1, 0, 1, 0, 0, 0, 0, 1;
  check_signed_svd(P, "odd permutation");
  P << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  check_signed_svd(P, "even permutation");
}

TEST(SignedSVD, KnownSignedValues)
{
  std::mt19937_64 rng(11u);
  const Vector3d cases[] = {{3, 2, 0.5}, {3, 2, -0.5}, {2, 2, 1}, {2, 1, 1}, {2, 2, -2},
                            {1, 1, -1e-6}, {5, 1e-3, -1e-7}, {1e8, 1, 1e-8}};
  for (const Vector3d& s : cases) {
    for (int i = 0; i < 50; ++i) {
      const Matrix3d F = PeriSISSMTest::rotated_diag(rng, s);
      check_signed_svd(F, "rotated diag");
      const SignedSVD d = signed_svd(F);
      EXPECT_LE((d.s - s).cwiseAbs().maxCoeff(), kTol * s.cwiseAbs().maxCoeff())
          << "expected " << s.transpose() << " got " << d.s.transpose();
    }
    if (HasFailure()) return;
  }
}

TEST(SignedSVD, RepeatedSingularValues)
{
  std::mt19937_64 rng(13u);
  for (int i = 0; i < 200; ++i) {
    const Matrix3d R = PeriSISSMTest::random_rotation(rng);
    check_signed_svd(R, "rotation");
    check_signed_svd(3.0 * R, "3 R");
    check_signed_svd(-2.0 * R, "-2 R");
    check_signed_svd(PeriSISSMTest::rotated_diag(rng, Vector3d(2, 2, 1)), "(2,2,1)");
    check_signed_svd(PeriSISSMTest::rotated_diag(rng, Vector3d(2, 1, 1)), "(2,1,1)");
    check_signed_svd(PeriSISSMTest::rotated_diag(rng, Vector3d(2, 1, -1)), "(2,1,-1)");
    if (HasFailure()) return;
  }
}

TEST(SignedSVD, RankDeficient)
{
  std::mt19937_64 rng(17u);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Vector3d a(n01(rng), n01(rng), n01(rng));
    const Vector3d b(n01(rng), n01(rng), n01(rng));
    const Vector3d c(n01(rng), n01(rng), n01(rng));
    const Matrix3d rank1 = a * b.transpose();
    const Matrix3d rank2 = a * b.transpose() + c * a.transpose();
    check_signed_svd(rank1, "rank 1");
    check_signed_svd(rank2, "rank 2");
    const SignedSVD d1 = signed_svd(rank1);
    EXPECT_NEAR(d1.s(0), a.norm() * b.norm(), 1e-12 * a.norm() * b.norm());
    EXPECT_LE(std::abs(d1.s(1)) + std::abs(d1.s(2)), 1e-12 * d1.s(0));
    check_signed_svd(PeriSISSMTest::rotated_diag(rng, Vector3d(1, 1, 0)), "(1,1,0)");
    check_signed_svd(PeriSISSMTest::rotated_diag(rng, Vector3d(1, 0, 0)), "(1,0,0)");
    if (HasFailure()) return;
  }
}

TEST(SignedSVD, NonFiniteInputIsFlagged)
{
  Matrix3d F = Matrix3d::Identity();
  F(1, 2) = std::numeric_limits<double>::quiet_NaN();
  const SignedSVD d = signed_svd(F);
  EXPECT_TRUE(d.s.array().isNaN().all());
  EXPECT_EQ(d.U, Matrix3d::Identity());
  EXPECT_EQ(d.V, Matrix3d::Identity());
  F(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(signed_svd(F).s.array().isNaN().all());
}

}  // namespace
