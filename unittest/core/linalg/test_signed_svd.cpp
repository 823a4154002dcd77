// Tests of the two signed SVDs, signed_svd() (the reference) and fast_signed_svd() (the one the
// force evaluation uses): reconstruction, orthonormality, proper rotations, ordering and the
// sign convention, on random F of every family and on the special cases that break naive code;
// and the fast one against the reference.

#include "linalg/fast_svd.h"
#include "linalg/signed_svd.h"
#include "materials/material.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSM::SignedSVD;
using PeriSISSMTest::max_abs;

// Tolerances: Jacobi SVD reconstructs to a few eps relative to |F| and accumulates U, V from
// O(10) plane rotations, so 1e-12 leaves two orders of magnitude of head room.
constexpr double kTol = 1e-12;

using Svd = SignedSVD (*)(const Matrix3d &);

// Every test below runs for both implementations.
class SignedSVDTest : public ::testing::TestWithParam<Svd> {
 protected:
  SignedSVD signed_svd(const Matrix3d &F) const { return GetParam()(F); }
  void check_signed_svd(const Matrix3d &F, const std::string &label) const;
};

// Every property of the contract, for one F. label names the case in failure messages.
void SignedSVDTest::check_signed_svd(const Matrix3d &F, const std::string &label) const
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

TEST_P(SignedSVDTest, RandomFamilies)
{
  for (const auto &sample : PeriSISSMTest::random_samples(20240601u)) {
    check_signed_svd(sample.F, PeriSISSMTest::family_name(sample.family));
    if (HasFailure()) return;
  }
}

TEST_P(SignedSVDTest, ExtremeScales)
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

TEST_P(SignedSVDTest, Identity)
{
  const SignedSVD d = signed_svd(Matrix3d::Identity());
  EXPECT_EQ(d.s, Vector3d::Ones());
  check_signed_svd(Matrix3d::Identity(), "I");
}

TEST_P(SignedSVDTest, Zero)
{
  const SignedSVD d = signed_svd(Matrix3d::Zero());
  EXPECT_EQ(d.s, Vector3d::Zero());
  check_signed_svd(Matrix3d::Zero(), "0");
}

TEST_P(SignedSVDTest, MinusIdentityAndReflections)
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

TEST_P(SignedSVDTest, KnownSignedValues)
{
  std::mt19937_64 rng(11u);
  const Vector3d cases[] = {{3, 2, 0.5}, {3, 2, -0.5},  {2, 2, 1},        {2, 1, 1},
                            {2, 2, -2},  {1, 1, -1e-6}, {5, 1e-3, -1e-7}, {1e8, 1, 1e-8}};
  for (const Vector3d &s : cases) {
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

TEST_P(SignedSVDTest, RepeatedSingularValues)
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

TEST_P(SignedSVDTest, RankDeficient)
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

TEST_P(SignedSVDTest, NonFiniteInputIsFlagged)
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

// The fast SVD against the reference: the same signed singular values, and the same isotropic
// functions U diag(g(s)) V^T (the first Piola-Kirchhoff stress of every model, the Kirchhoff-like
// U diag(g(s)) U^T) where U and V themselves may differ (repeated singular values). Tolerance:
// both reconstruct F to a few eps |F|, so s agree to ~1e-15 |s|max; the stresses inherit the
// error of the vectors, times at most the largest |dW/ds| slope over the spread of s: 1e-11
// relative to the largest stress entry (plus the forward error below) leaves 100x head room over
// the worst case seen.
TEST(FastSignedSVD, AgreesWithReference)
{
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  std::vector<Matrix3d> cases;
  for (const auto &sample : PeriSISSMTest::random_samples(20261126u)) cases.push_back(sample.F);
  std::mt19937_64 rng(29u);
  for (const Vector3d &s : {Vector3d(1, 1, 1), Vector3d(1, 1, 1 + 1e-9), Vector3d(1 + 1e-6, 1, 1),
                            Vector3d(2, 2, 1), Vector3d(2, 1, -1 + 1e-12), Vector3d(1, 0, 0),
                            Vector3d(1e8, 1, 1e-8), Vector3d(5, 1e-3, -1e-7)})
    for (int i = 0; i < 50; ++i) cases.push_back(PeriSISSMTest::rotated_diag(rng, s));
  for (int i = 0; i < 200; ++i)    // the common case of a force evaluation: small strains
    cases.push_back(PeriSISSMTest::random_rotation(rng) *
                    (Matrix3d::Identity() + 1e-6 * PeriSISSMTest::gaussian_matrix(rng)));

  std::vector<std::unique_ptr<PeriSISSM::Material>> models;
  for (const std::string &name : PeriSISSM::material_names())
    models.push_back(PeriSISSM::make_material(name, 1.0, 2.0));
  for (const Matrix3d &F : cases) {
    const SignedSVD r = PeriSISSM::signed_svd(F), f = PeriSISSM::fast_signed_svd(F);
    const double smax = r.s.cwiseAbs().maxCoeff();
    ASSERT_LE((r.s - f.s).cwiseAbs().maxCoeff(), 1e-13 * smax) << "F =\n" << F;
    for (const auto &m : models) {
      // the corotated model's P = U (2 mu (s - 1) + ...) V^T is not unique where s_2 + s_3 = 0
      // (its kink of inverted F, material_linear.h, and rank < 2, where the rotation U V^T
      // is not defined); nor is xu's, whose energy is not even in s either (material_xu.h)
      const std::string name = m->name();
      if ((name == "linear" || name == "xu") && r.s(1) + r.s(2) < 1e-2 * smax) continue;
      const Vector3d phat = m->principal_stress(r.s);
      if (!phat.allFinite()) continue;    // neo-Hookean at det F <= 0
      const Matrix3d Pr = r.U * phat.asDiagonal() * r.V.transpose();
      const Matrix3d Pf = f.U * m->principal_stress(f.s).asDiagonal() * f.V.transpose();
      // forward error: s_3 is known to eps s_1 only, and a model whose stress grows like 1/s
      // (neo-Hookean) turns that into a relative error of eps times the condition number
      const double kappa = smax / std::max(std::abs(r.s(2)), 1e-300);
      const double tol = 1e-11 * std::max(1.0, max_abs(Pr)) + 1e3 * kEps * kappa * max_abs(Pr);
      ASSERT_LE(max_abs(Pr - Pf), tol) << m->name() << " F =\n" << F;
    }
  }
}

// The same bits (a -0 and a +0 differ); a non-finite F's NaN s on both sides
bool same_bits(const SignedSVD &x, const SignedSVD &y)
{
  if (x.s.array().isNaN().any() || y.s.array().isNaN().any())
    return x.s.array().isNaN().all() && y.s.array().isNaN().all();
  return std::memcmp(x.U.data(), y.U.data(), sizeof(double) * 9) == 0 &&
      std::memcmp(x.V.data(), y.V.data(), sizeof(double) * 9) == 0 &&
      std::memcmp(x.s.data(), y.s.data(), sizeof(double) * 3) == 0;
}

// Two at once: each exactly as alone, whatever its partner (one may converge sweeps before the
// other, or be non-finite).
TEST(FastSignedSVD, PairsEqualSingles)
{
  std::vector<Matrix3d> cases;
  for (const auto &sample : PeriSISSMTest::random_samples(77u, 40)) cases.push_back(sample.F);
  cases.push_back(Matrix3d::Identity());
  cases.push_back(Matrix3d::Zero());
  Matrix3d bad = Matrix3d::Identity();
  bad(0, 1) = std::numeric_limits<double>::quiet_NaN();
  cases.push_back(bad);
  for (size_t i = 0; i < cases.size(); i++) {
    const size_t j = (7 * i + 3) % cases.size();
    SignedSVD a, b;
    PeriSISSM::fast_signed_svd(cases[i], cases[j], a, b);
    ASSERT_TRUE(same_bits(a, PeriSISSM::fast_signed_svd(cases[i]))) << "F =\n" << cases[i];
    ASSERT_TRUE(same_bits(b, PeriSISSM::fast_signed_svd(cases[j]))) << "F =\n" << cases[j];
  }
}

// Four at once (one per lane of 4-wide registers where the processor has AVX2): each exactly as
// alone, whatever the other three (sweeps to convergence differ from lane to lane; zero,
// identity, non-finite, scaled and inverted matrices among them).
TEST(FastSignedSVD, FoursEqualSingles)
{
  std::vector<Matrix3d> cases;
  for (const auto &sample : PeriSISSMTest::random_samples(91u, 40)) cases.push_back(sample.F);
  std::mt19937_64 rng(5u);
  for (int i = 0; i < 40; ++i)    // small strains, rotated: the common case
    cases.push_back(PeriSISSMTest::random_rotation(rng) *
                    (Matrix3d::Identity() + 1e-6 * PeriSISSMTest::gaussian_matrix(rng)));
  for (const Vector3d &s : {Vector3d(1, 1, 1 + 1e-9), Vector3d(2, 1, -1 + 1e-12), Vector3d(1, 0, 0),
                            Vector3d(1e8, 1, 1e-8)})
    for (int i = 0; i < 4; ++i) cases.push_back(PeriSISSMTest::rotated_diag(rng, s));
  // a nearly diagonal matrix, whose first sweep takes the small-angle branch, falls in the same
  // four as matrices that take the general one
  for (int i = 0; i < 8; ++i) {
    Matrix3d near = Vector3d(2, 1.5, 1).asDiagonal().toDenseMatrix();
    near(0, 1) = near(2, 1) = 1e-10 * (i + 1);
    cases.push_back(near);
  }
  cases.push_back(Matrix3d::Identity());
  cases.push_back(Matrix3d::Zero());
  cases.push_back(1e200 * PeriSISSMTest::random_rotation(rng));    // scaled by 2^-k first
  cases.push_back(1e-200 * PeriSISSMTest::gaussian_matrix(rng));
  Matrix3d bad = Matrix3d::Identity();
  bad(0, 1) = std::numeric_limits<double>::quiet_NaN();
  cases.push_back(bad);
  bad(0, 1) = std::numeric_limits<double>::infinity();
  cases.push_back(bad);
  const size_t n = cases.size();
  for (size_t i = 0; i < n; i++) {
    const Matrix3d F[4] = {cases[i], cases[(7 * i + 3) % n], cases[(13 * i + 5) % n],
                           cases[(i + n - 1) % n]};
    SignedSVD out[4];
    PeriSISSM::fast_signed_svd(F, out);
    for (int l = 0; l < 4; l++)
      ASSERT_TRUE(same_bits(out[l], PeriSISSM::fast_signed_svd(F[l]))) << "lane " << l << ", F =\n"
                                                                       << F[l];
  }
}

// A power-of-two scale of F scales s exactly and leaves U and V as they are, however far from 1
// (the convergence test squares Gram entries, fourth powers of F's entries: matrices with entries
// near 2^300 or 2^-300 were once left unrotated).
TEST(FastSignedSVD, PowerOfTwoScalesAreExact)
{
  std::mt19937_64 rng(17u);
  for (int i = 0; i < 20; ++i) {
    const Matrix3d F = PeriSISSMTest::gaussian_matrix(rng);
    const SignedSVD one = PeriSISSM::fast_signed_svd(F);
    for (int e : {-900, -600, -300, -150, 150, 300, 600, 900}) {
      const Matrix3d G = F.unaryExpr([e](double a) {
        return std::ldexp(a, e);
      });
      const SignedSVD scaled = PeriSISSM::fast_signed_svd(G);
      for (int k = 0; k < 3; k++)
        ASSERT_EQ(scaled.s(k), std::ldexp(one.s(k), e)) << "2^" << e << " F, F =\n" << F;
      ASSERT_TRUE((scaled.U.array() == one.U.array()).all()) << "2^" << e << ", F =\n" << F;
      ASSERT_TRUE((scaled.V.array() == one.V.array()).all()) << "2^" << e << ", F =\n" << F;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Implementations, SignedSVDTest,
                         ::testing::Values(&PeriSISSM::signed_svd,
                                           static_cast<Svd>(&PeriSISSM::fast_signed_svd)),
                         [](const ::testing::TestParamInfo<Svd> &info) {
                           return std::string(info.index == 0 ? "Reference" : "Fast");
                         });

}    // namespace
