// Tests of the correspondence of one particle (peri/particle.h) and of the family helpers
// singularity test, the partial-volume factor, the stabilization modulus, the per-particle
// state F, A = P K^-1, W, and the Cauchy and von Mises stresses.

#include "materials/material.h"
#include "peri/family.h"
#include "peri/particle.h"
#include "peri/stabilization.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSMTest::max_abs;
using RowMatrix3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

constexpr double kPi = 3.14159265358979323846;

// Row-major double[9] <-> Eigen.
std::array<double, 9> to_array(const Matrix3d &A)
{
  std::array<double, 9> out;
  Eigen::Map<RowMatrix3d>(out.data()) = A;
  return out;
}

Matrix3d to_matrix(const double *a)
{
  return Eigen::Map<const RowMatrix3d>(a);
}

// A bond of a family: reference bond xi and weight omega = beta V_j.
struct Bond {
  Vector3d xi;
  double omega;
};

// Family of a particle at the origin of a simple cubic lattice of spacing a (particle volume
// a^3), with the rules of pair peri/nosb: partners with 0 < |xi| <= cutoff, omega = beta V with
// the partial-volume factor of horizon delta and particle size h = a. keep(x) selects the
// lattice sites that exist (a surface cuts the family). cutoff = delta is what the pair builds;
// cutoff = delta + a/2 keeps the whole ramp of beta.
std::vector<Bond> lattice_family(double a, double delta, double cutoff,
                                 const std::function<bool(const Vector3d &)> &keep)
{
  std::vector<Bond> bonds;
  const int n = static_cast<int>(std::ceil(cutoff / a)) + 1;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const Vector3d xi(i * a, j * a, k * a);
        const double r = xi.norm();
        if (r > cutoff || !keep(xi)) continue;
        bonds.push_back({xi, PeriSISSM::partial_volume_factor(r, delta, a) * a * a * a});
      }
  return bonds;
}

std::vector<Bond> bulk_family(double a, double delta)
{
  return lattice_family(a, delta, delta, [](const Vector3d &) {
    return true;
  });
}

Matrix3d shape_tensor(const std::vector<Bond> &bonds)
{
  Matrix3d K = Matrix3d::Zero();
  for (const Bond &b : bonds) K += b.omega * b.xi * b.xi.transpose();
  return K;
}

// M = sum omega eta (x) xi for the current bonds eta = F xi (affine deformation).
Matrix3d affine_moment(const std::vector<Bond> &bonds, const Matrix3d &F)
{
  Matrix3d M = Matrix3d::Zero();
  for (const Bond &b : bonds) M += b.omega * (F * b.xi) * b.xi.transpose();
  return M;
}

// Symmetric matrix from xx yy zz xy xz yz.
Matrix3d sigma_matrix(const double s[6])
{
  Matrix3d S;
  S << s[0], s[3], s[4], s[3], s[1], s[5], s[4], s[5], s[2];
  return S;
}

// lambda_min / lambda_max of K.
double conditioning(const Matrix3d &K)
{
  const Vector3d lam = Eigen::SelfAdjointEigenSolver<Matrix3d>(K).eigenvalues();
  return lam(0) / lam(2);
}

// Invert through the function under test; expects success.
Matrix3d inverse_of(const Matrix3d &K, double lambda_ref = 0.0)
{
  const auto k = to_array(K);
  std::array<double, 9> kinv;
  EXPECT_TRUE(PeriSISSM::invert_shape_tensor(k.data(), lambda_ref, kinv.data()));
  return to_matrix(kinv.data());
}

// ---------------------------------------------------------------------------------------------
// invert_shape_tensor

// Interior particle (full sphere of bonds, horizon 3a): regular, K^-1 symmetric, K K^-1 = I to
// round-off (K is nearly isotropic, condition number ~1), lambda_max reported.
TEST(InvertShapeTensor, FullSphereIsRegular)
{
  const double a = 0.5e-3;    // the impact example's spacing: K ~ 1e-21 in SI units
  const Matrix3d K = shape_tensor(bulk_family(a, 3.0002 * a));
  const auto k = to_array(K);
  std::array<double, 9> kinv;
  double lmax = -1.0;
  ASSERT_TRUE(PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data(), &lmax));
  const Matrix3d Kinv = to_matrix(kinv.data());
  EXPECT_EQ(Kinv, Kinv.transpose());
  EXPECT_LE(max_abs(K * Kinv - Matrix3d::Identity()), 1e-14);
  EXPECT_LE(max_abs(Kinv * K - Matrix3d::Identity()), 1e-14);
  EXPECT_NEAR(lmax, Eigen::SelfAdjointEigenSolver<Matrix3d>(K).eigenvalues()(2), 1e-12 * lmax);
}

// The conditioning of intact particles near surfaces, as stated in peri/family.h (simple
// cubic lattice, horizon 3a): face 0.77, edge 0.36, corner 0.28, corner of a two-layer plate
// 0.11, all above kMinShapeConditioning and all inverted to round-off times the condition
// number. A one-layer plate (all bonds in a plane) is singular.
TEST(InvertShapeTensor, SurfaceParticlesOfAnIntactBody)
{
  const double a = 1.0, delta = 3.0002;
  struct Case {
    const char *name;
    std::function<bool(const Vector3d &)> keep;
    double ratio;
  };
  const std::vector<Case> cases = {
      {"interior",
       [](const Vector3d &) {
         return true;
       },
       1.0},
      {"face",
       [](const Vector3d &x) {
         return x(2) >= 0.0;
       },
       0.77},
      {"edge",
       [](const Vector3d &x) {
         return x(1) >= 0.0 && x(2) >= 0.0;
       },
       0.36},
      {"corner",
       [](const Vector3d &x) {
         return (x.array() >= 0.0).all();
       },
       0.28},
      {"corner of a two-layer plate",
       [](const Vector3d &x) {
         return x(0) >= 0.0 && x(1) >= 0.0 && x(2) >= 0.0 && x(2) <= 1.0;
       },
       0.11},
  };
  for (const Case &c : cases) {
    SCOPED_TRACE(c.name);
    const Matrix3d K = shape_tensor(lattice_family(a, delta, delta, c.keep));
    const double ratio = conditioning(K);
    EXPECT_NEAR(ratio, c.ratio, 0.005);
    EXPECT_GT(ratio, PeriSISSM::kMinShapeConditioning);
    const Matrix3d Kinv = inverse_of(K);
    EXPECT_LE(max_abs(K * Kinv - Matrix3d::Identity()), 1e-14 / ratio);
  }
  const Matrix3d plate = shape_tensor(lattice_family(a, delta, delta, [](const Vector3d &x) {
    return x(2) == 0.0;
  }));
  const auto k = to_array(plate);
  std::array<double, 9> kinv;
  EXPECT_FALSE(PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data()));
}

// Families spanning fewer than three directions are singular: K^-1 all zeros, false.
TEST(InvertShapeTensor, PlanarCollinearAndEmptyFamiliesAreSingular)
{
  std::mt19937_64 rng(17u);
  const Matrix3d Q = PeriSISSMTest::random_rotation(rng);
  std::vector<Bond> planar, collinear, two;
  for (int b = 0; b < 40; ++b) {
    const double u = PeriSISSMTest::uniform(rng, -1, 1), v = PeriSISSMTest::uniform(rng, -1, 1);
    planar.push_back({Q * Vector3d(u, v, 0.0), 1.0});
    collinear.push_back({Q * Vector3d(u, 0.0, 0.0), 1.0});
  }
  two.push_back({Vector3d(1, 0, 0), 1.0});
  two.push_back({Vector3d(0, 1, 0), 1.0});
  struct Case {
    const char *name;
    Matrix3d K;
  };
  for (const Case &c :
       {Case{"planar", shape_tensor(planar)}, Case{"collinear", shape_tensor(collinear)},
        Case{"two partners", shape_tensor(two)},
        Case{"one partner", shape_tensor({{Vector3d(1, 2, 3), 1.0}})},
        Case{"empty", Matrix3d::Zero()}}) {
    SCOPED_TRACE(c.name);
    const auto k = to_array(c.K);
    std::array<double, 9> kinv;
    kinv.fill(7.0);
    double lmax = -1.0;
    EXPECT_FALSE(PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data(), &lmax));
    for (double v : kinv) EXPECT_EQ(v, 0.0);
    EXPECT_GE(lmax, 0.0);
  }
}

// lambda_min >= kMinShapeConditioning * max(lambda_max, lambda_ref) is the regular range, in
// any orientation. The closed-form eigenvalues are accurate to ~1e-8 relative to lambda_max,
// so the test stays 1e-6 away from the threshold.
TEST(InvertShapeTensor, ConditioningThreshold)
{
  const double c = PeriSISSM::kMinShapeConditioning;
  std::mt19937_64 rng(19u);
  for (int trial = 0; trial < 20; ++trial) {
    const Matrix3d Q = trial == 0 ? Matrix3d::Identity() : PeriSISSMTest::random_rotation(rng);
    const double scale = std::pow(10.0, PeriSISSMTest::uniform(rng, -25.0, 25.0));
    for (double factor : {1.0 - 1e-6, 1.0 + 1e-6}) {
      const Matrix3d K = scale * Q * Vector3d(1.0, 0.5, c * factor).asDiagonal() * Q.transpose();
      const auto k = to_array(K);
      std::array<double, 9> kinv;
      double lmax = 0.0;
      const bool regular = PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data(), &lmax);
      EXPECT_EQ(regular, factor > 1.0) << "trial " << trial;
      EXPECT_NEAR(lmax, scale, 1e-8 * scale);
      if (regular) {
        EXPECT_LE(max_abs(K * to_matrix(kinv.data()) - Matrix3d::Identity()), 1e-13 / c);
      }
    }
  }
  // The reference eigenvalue: an isotropic K = 0.1 I is regular on its own and against a
  // reference of 1 (ratio 0.1), singular against a reference of 3 (0.1 < 0.05 * 3): a family
  // shrunk by fracture to a small fraction of its initial size.
  const auto k = to_array(0.1 * Matrix3d::Identity());
  std::array<double, 9> kinv;
  EXPECT_TRUE(PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data()));
  EXPECT_TRUE(PeriSISSM::invert_shape_tensor(k.data(), 1.0, kinv.data()));
  EXPECT_NEAR(kinv[0], 10.0, 1e-14);
  EXPECT_FALSE(PeriSISSM::invert_shape_tensor(k.data(), 3.0, kinv.data()));
  for (double v : kinv) EXPECT_EQ(v, 0.0);
  // A reference smaller than lambda_max has no effect.
  EXPECT_TRUE(PeriSISSM::invert_shape_tensor(k.data(), 0.01, kinv.data()));
}

// Non-finite input: false, zeros, lambda_max 0 (never NaN out).
TEST(InvertShapeTensor, NonFiniteInput)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int entry = 0; entry < 9; ++entry) {
    for (double bad : {nan, inf, -inf}) {
      auto k = to_array(Matrix3d::Identity());
      k[entry] = bad;
      std::array<double, 9> kinv;
      kinv.fill(7.0);
      double lmax = 7.0;
      EXPECT_FALSE(PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data(), &lmax));
      for (double v : kinv) EXPECT_EQ(v, 0.0);
      EXPECT_EQ(lmax, 0.0);
    }
  }
  // a non-finite reference cannot make a finite K regular by accident
  const auto k = to_array(Matrix3d::Identity());
  std::array<double, 9> kinv;
  EXPECT_FALSE(PeriSISSM::invert_shape_tensor(k.data(), inf, kinv.data()));
}

// Random well-conditioned SPD K over extreme scales: K K^-1 = I to round-off times the condition
// number; lambda_max optional.
TEST(InvertShapeTensor, InverseOfRandomSpdMatrices)
{
  std::mt19937_64 rng(23u);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d lam(1.0, PeriSISSMTest::uniform(rng, 0.06, 1.0),
                       PeriSISSMTest::uniform(rng, 0.06, 1.0));
    const double scale = std::pow(10.0, PeriSISSMTest::uniform(rng, -30.0, 30.0));
    const Matrix3d Q = PeriSISSMTest::random_rotation(rng);
    const Matrix3d K = scale * Q * lam.asDiagonal() * Q.transpose();
    const auto k = to_array(K);
    std::array<double, 9> kinv;
    ASSERT_TRUE(PeriSISSM::invert_shape_tensor(k.data(), 0.0, kinv.data()));
    const Matrix3d Kinv = to_matrix(kinv.data());
    EXPECT_EQ(Kinv, Kinv.transpose());
    EXPECT_LE(max_abs(K * Kinv - Matrix3d::Identity()), 1e-14 / lam.minCoeff()) << trial;
  }
}

// ---------------------------------------------------------------------------------------------
// partial_volume_factor

TEST(PartialVolumeFactor, InsideRampBeyond)
{
  const double delta = 3.0, h = 1.0;
  EXPECT_EQ(PeriSISSM::partial_volume_factor(0.0, delta, h), 1.0);
  EXPECT_EQ(PeriSISSM::partial_volume_factor(1.0, delta, h), 1.0);
  EXPECT_EQ(PeriSISSM::partial_volume_factor(2.5, delta, h), 1.0);    // delta - h/2
  EXPECT_EQ(PeriSISSM::partial_volume_factor(2.75, delta, h), 0.75);
  EXPECT_EQ(PeriSISSM::partial_volume_factor(3.0, delta, h), 0.5);    // delta: half
  EXPECT_EQ(PeriSISSM::partial_volume_factor(3.25, delta, h), 0.25);
  EXPECT_EQ(PeriSISSM::partial_volume_factor(3.5, delta, h), 0.0);    // delta + h/2
  EXPECT_EQ(PeriSISSM::partial_volume_factor(3.6, delta, h), 0.0);
  EXPECT_EQ(PeriSISSM::partial_volume_factor(1e300, delta, h), 0.0);
}

// Linear on the ramp (constant slope -1/h), within [0, 1] and non-increasing everywhere,
// continuous at both ends of the ramp (one ulp on either side changes beta by ~ulp/h).
TEST(PartialVolumeFactor, LinearMonotoneAndContinuous)
{
  for (double scale : {1e-8, 1.0, 1e8}) {
    const double delta = 3.0002 * scale, h = 1.3 * scale;
    double prev = 1.0;
    for (int k = 0; k <= 1000; ++k) {
      const double r = 5.0 * scale * k / 1000.0;
      const double beta = PeriSISSM::partial_volume_factor(r, delta, h);
      EXPECT_GE(beta, 0.0);
      EXPECT_LE(beta, 1.0);
      EXPECT_LE(beta, prev);
      prev = beta;
      if (r > delta - 0.5 * h && r < delta + 0.5 * h) {
        const double dr = 1e-3 * h;
        const double slope = (PeriSISSM::partial_volume_factor(r + dr, delta, h) -
                              PeriSISSM::partial_volume_factor(r, delta, h)) /
            dr;
        if (r + dr < delta + 0.5 * h) { EXPECT_NEAR(slope, -1.0 / h, 1e-9 / h) << "r = " << r; }
      }
    }
    for (double edge : {delta - 0.5 * h, delta + 0.5 * h}) {
      const double lo = std::nextafter(edge, 0.0), hi = std::nextafter(edge, 2.0 * edge);
      EXPECT_NEAR(PeriSISSM::partial_volume_factor(lo, delta, h),
                  PeriSISSM::partial_volume_factor(hi, delta, h), 1e-14);
      EXPECT_NEAR(PeriSISSM::partial_volume_factor(edge, delta, h),
                  PeriSISSM::partial_volume_factor(hi, delta, h), 1e-14);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// stabilization_modulus

// Continuum full sphere, w = 1: K = (4 pi delta^5 / 15) I, so C = (8/5) Cs K tr(K^-1)
// = Cs 18 K / (pi delta^5) up to round-off.
TEST(StabilizationModulus, ContinuumBulkValue)
{
  for (double delta : {1e-3, 1.5e-3, 1.0, 7.0}) {
    const Matrix3d Kshape = (4.0 * kPi * std::pow(delta, 5) / 15.0) * Matrix3d::Identity();
    const Matrix3d Kinv = inverse_of(Kshape);
    for (double Cs : {0.0, 0.1, 1.0, 2.0}) {
      const double bulk = 14.9e9;
      const double C = PeriSISSM::stabilization_modulus(Cs, bulk, to_array(Kinv).data());
      const double expected = Cs * 18.0 * bulk / (kPi * std::pow(delta, 5));
      EXPECT_NEAR(C, expected, 1e-14 * expected) << "delta " << delta << " Cs " << Cs;
    }
  }
}

// Dense lattice families approach the continuum value as m = delta / a grows.
// - With the whole ramp of beta (partners up to delta + a/2) the lattice sum is a midpoint-rule
//   approximation of the integral over the ball; measured |C / C_bulk - 1| <= 0.45 a / delta for
//   every delta in [2a, 20a] (the shell of lattice sites fluctuates), and much less at integer
//   m (9.4% at m = 3, 1.9% at m = 6, 0.2% at m = 20): asserted <= 0.5 a / delta and
//   converging.
// - The families pair peri/nosb builds stop at delta (r <= delta, as the built-in PERI styles):
//   the cut-off half of the ramp, delta < r <= delta + a/2 with beta from 1/2 to 0, holds
//   ~ int beta r^4 dr / int_0^delta r^4 dr ~ 5 a / (8 delta) of the continuum K, so C in the
//   bulk is higher than Cs 18K/(pi delta^5) by about that much plus the fluctuation above:
//   +12.8% at delta = 3.0002a (the example decks). Asserted within (0, (5/8 + 1/2) a/delta].
TEST(StabilizationModulus, LatticeBulkValue)
{
  const double a = 1.0, bulk = 1.0, Cs = 2.0;
  auto ratio = [&](double m, bool whole_ramp) {
    const double delta = m * a;
    const auto bonds =
        lattice_family(a, delta, whole_ramp ? delta + 0.5 * a : delta, [](const Vector3d &) {
          return true;
        });
    const Matrix3d Kinv = inverse_of(shape_tensor(bonds));
    return PeriSISSM::stabilization_modulus(Cs, bulk, to_array(Kinv).data()) /
        (Cs * 18.0 * bulk / (kPi * std::pow(delta, 5)));
  };
  for (double m : {3.0, 3.0002, 4.0, 6.0, 10.0, 20.0}) {
    const double whole = ratio(m, true) - 1.0;
    EXPECT_LE(std::abs(whole), 0.5 / m) << "m = " << m;
    const double cut = ratio(m, false) - 1.0;
    EXPECT_GT(cut, 0.0) << "m = " << m;
    EXPECT_LE(cut, (0.625 + 0.5) / m) << "m = " << m;
  }
  EXPECT_LT(std::abs(ratio(20.0, true) - 1.0), 0.1 * std::abs(ratio(3.0, true) - 1.0));
  EXPECT_NEAR(ratio(3.0002, false), 1.128, 0.001);
}

// Linear in Cs and K; grows where the family is cut (K^-1 larger): face and corner particles
// get a larger C than interior ones.
TEST(StabilizationModulus, ScalesWithFamily)
{
  const double a = 1.0, delta = 3.0002;
  const auto kinv_of = [&](const std::function<bool(const Vector3d &)> &keep) {
    return to_array(inverse_of(shape_tensor(lattice_family(a, delta, delta, keep))));
  };
  const auto interior = kinv_of([](const Vector3d &) {
    return true;
  });
  const auto face = kinv_of([](const Vector3d &x) {
    return x(2) >= 0.0;
  });
  const auto corner = kinv_of([](const Vector3d &x) {
    return (x.array() >= 0.0).all();
  });
  const double ci = PeriSISSM::stabilization_modulus(1.0, 1.0, interior.data());
  EXPECT_DOUBLE_EQ(PeriSISSM::stabilization_modulus(2.0, 3.0, interior.data()), 6.0 * ci);
  EXPECT_EQ(PeriSISSM::stabilization_modulus(0.0, 3.0, interior.data()), 0.0);
  const double cf = PeriSISSM::stabilization_modulus(1.0, 1.0, face.data());
  const double cc = PeriSISSM::stabilization_modulus(1.0, 1.0, corner.data());
  EXPECT_GT(cf, ci);
  EXPECT_GT(cc, cf);
}

// ---------------------------------------------------------------------------------------------
// correspondence_state

std::vector<Matrix3d> affine_gradients()
{
  std::mt19937_64 rng(29u);
  const Matrix3d R = PeriSISSMTest::random_rotation(rng);
  Matrix3d shear = Matrix3d::Identity();
  shear(0, 1) = 0.3;
  return {
      Matrix3d::Identity(),
      Vector3d(1.01, 1.0, 1.0).asDiagonal(),                  // uniaxial stretch
      Vector3d(1.2, 0.9, 1.05).asDiagonal(),                  // triaxial
      shear,                                                  // simple shear
      0.6 * Matrix3d::Identity(),                             // compression
      R,                                                      // rotation
      R * Matrix3d(Vector3d(1.3, 0.8, 1.1).asDiagonal()),     // rotation + stretch
      R * Matrix3d(Vector3d(1.0, 1.0, -0.4).asDiagonal()),    // inverted
  };
}

// Affine deformation eta = F xi: M = F K, so F comes back to round-off times the condition
// number of K (the formula is exact), A = P(F) K^-1 (A K = P, the force state carries the stress:
// sum_j omega (A xi) (x) xi = P), and the returned W is W(F). For interior, face and corner
// particles and every model.
TEST(CorrespondenceState, AffineDeformationGivesBackF)
{
  const double a = 0.5e-3, delta = 3.0002 * a;
  const std::vector<std::function<bool(const Vector3d &)>> keeps = {
      [](const Vector3d &) {
        return true;
      },
      [](const Vector3d &x) {
        return x(2) >= 0.0;
      },
      [](const Vector3d &x) {
        return (x.array() >= 0.0).all();
      },
  };
  for (const std::string &name : PeriSISSM::material_names()) {
    const auto m = PeriSISSM::make_material(name, 6.0e9, 5.0e9);
    for (size_t f = 0; f < keeps.size(); ++f) {
      const auto bonds = lattice_family(a, delta, delta, keeps[f]);
      const Matrix3d K = shape_tensor(bonds);
      const auto kinv = to_array(inverse_of(K));
      const double cond = 1.0 / conditioning(K);
      for (const Matrix3d &F : affine_gradients()) {
        SCOPED_TRACE(name + " family " + std::to_string(f));
        const auto M = to_array(affine_moment(bonds, F));
        std::array<double, 9> fout, aout;
        const double W =
            PeriSISSM::correspondence_state(*m, M.data(), kinv.data(), fout.data(), aout.data());
        const Matrix3d Fo = to_matrix(fout.data()), A = to_matrix(aout.data());
        EXPECT_LE(max_abs(Fo - F), 1e-14 * cond * max_abs(F));
        // errors relative to the modulus: P at F = I or a rotation is zero, and F itself
        // carries round-off of ~1e-16 cond, which P turns into ~1e-16 cond * modulus
        const Matrix3d P = PeriSISSM::first_piola(*m, F);
        const double modulus = m->mu() + std::abs(m->lambda());
        const double pscale = max_abs(P) + modulus;
        EXPECT_LE(max_abs(A * K - P), 1e-12 * cond * pscale);
        EXPECT_LE(max_abs(A - P * to_matrix(kinv.data())),
                  1e-12 * cond * pscale * max_abs(to_matrix(kinv.data())));
        Matrix3d T = Matrix3d::Zero();
        for (const Bond &b : bonds) T += b.omega * (A * b.xi) * b.xi.transpose();
        EXPECT_LE(max_abs(T - P), 1e-12 * cond * pscale);
        const double W0 = PeriSISSMTest::energy_of_F(*m, F);
        EXPECT_NEAR(W, W0, 1e-13 * cond * (std::abs(W0) + max_abs(P) + 1e-3 * modulus));
        EXPECT_EQ(W, PeriSISSMTest::energy_of_F(*m, Fo));
      }
    }
  }
}

// At rest (eta = xi) every model gives F = I to round-off, zero stress state and W = 0 to
// round-off.
TEST(CorrespondenceState, RestState)
{
  const double a = 1.0;
  const auto bonds = bulk_family(a, 3.0002 * a);
  const Matrix3d K = shape_tensor(bonds);
  const auto kinv = to_array(inverse_of(K));
  const auto M = to_array(K);
  for (const std::string &name : PeriSISSM::material_names()) {
    const auto m = PeriSISSM::make_material(name, 1.0, 1.5);
    std::array<double, 9> fout, aout;
    const double W =
        PeriSISSM::correspondence_state(*m, M.data(), kinv.data(), fout.data(), aout.data());
    EXPECT_LE(max_abs(to_matrix(fout.data()) - Matrix3d::Identity()), 1e-14) << name;
    EXPECT_LE(max_abs(to_matrix(aout.data()) * K), 1e-13) << name;
    EXPECT_LE(std::abs(W), 1e-26) << name;
  }
}

// The overload with the SISSM implicit stiffness: the same F, A and W as the plain one, and
// H = kappa U diag(c) U^T (kappa = tr(K^-1)/3), i.e. kappa times the stiffness direction of
// particle_stress(): symmetric positive semi-definite, kappa (2 mu + lambda) I for linear.
TEST(CorrespondenceState, ImplicitStiffnessOverload)
{
  const double a = 1.0;
  const auto bonds = lattice_family(a, 3.0002 * a, 3.0002 * a, [](const Vector3d &x) {
    return x(2) >= 0.0;
  });
  const Matrix3d K = shape_tensor(bonds);
  const auto kinv = to_array(inverse_of(K));
  const double kappa = (kinv[0] + kinv[4] + kinv[8]) / 3.0;
  for (const std::string &name : PeriSISSM::material_names()) {
    for (const auto &c : PeriSISSMTest::material_cases()) {
      SCOPED_TRACE(name + " " + c.label);
      const auto m = PeriSISSM::make_material(name, c.mu, c.lambda);
      const double modulus = c.mu + std::abs(c.lambda);
      for (const auto &sample : PeriSISSMTest::random_samples(41u, 10)) {
        const auto M = to_array(affine_moment(bonds, sample.F));
        std::array<double, 9> f1, a1, f2, a2;
        double h[6];
        const double W1 =
            PeriSISSM::correspondence_state(*m, M.data(), kinv.data(), f1.data(), a1.data());
        const double W2 =
            PeriSISSM::correspondence_state(*m, M.data(), kinv.data(), f2.data(), a2.data(), h);
        EXPECT_EQ(W1, W2);
        EXPECT_EQ(f1, f2);
        EXPECT_EQ(a1, a2);
        const Matrix3d H = sigma_matrix(h);
        PeriSISSM::ParticleStress ps;
        PeriSISSM::particle_stress(*m, to_matrix(f1.data()), ps, true);
        // round-off relative to the largest stiffness entry (the neo-Hookean c grows with the
        // volumetric curvature far from rest, beyond mu + |lambda|)
        const double scale =
            std::max(modulus, PeriSISSM::implicit_direction(ps).cwiseAbs().maxCoeff());
        EXPECT_LE(max_abs(H - kappa * PeriSISSM::implicit_direction(ps)), 1e-13 * kappa * scale);
        EXPECT_GE(Eigen::SelfAdjointEigenSolver<Matrix3d>(H).eigenvalues().minCoeff(),
                  -1e-13 * kappa * scale);
        if (name == "linear") {
          EXPECT_LE(max_abs(H - kappa * (2.0 * c.mu + c.lambda) * Matrix3d::Identity()),
                    1e-13 * kappa * modulus);
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// cauchy_stress, von_mises

// sigma = P F^T / J for J > 1e-3: P F^T (the Kirchhoff stress) is symmetric for these
// isotropic models, and the function returns its components divided by J, J = det F and W(F).
TEST(CauchyStress, EqualsPFTOverJ)
{
  for (const std::string &name : PeriSISSM::material_names()) {
    for (const auto &c : PeriSISSMTest::material_cases()) {
      SCOPED_TRACE(name + " " + c.label);
      const auto m = PeriSISSM::make_material(name, c.mu, c.lambda);
      for (const auto &sample : PeriSISSMTest::random_samples(31u, 20)) {
        const Matrix3d &F = sample.F;
        const auto f = to_array(F);
        double s[6], J = 0.0;
        const double W = PeriSISSM::cauchy_stress(*m, f.data(), s, J);
        const double detF = F.determinant();
        EXPECT_NEAR(J, detF, 1e-12 * std::pow(F.norm(), 3));
        EXPECT_EQ(W, PeriSISSMTest::energy_of_F(*m, F));
        for (double v : s) EXPECT_TRUE(std::isfinite(v));
        // tau = P F^T: round-off relative to |P| |F| (tau itself can be much smaller)
        const Matrix3d P = PeriSISSM::first_piola(*m, F);
        const Matrix3d tau = P * F.transpose();
        const double tscale = max_abs(P) * F.cwiseAbs().rowwise().sum().maxCoeff() + 1e-300;
        EXPECT_LE(max_abs(tau - tau.transpose()), 1e-12 * tscale);
        if (J > PeriSISSM::kCauchyMinJ) {
          EXPECT_LE(max_abs(sigma_matrix(s) - tau / J), 1e-12 * tscale / J);
        } else {
          EXPECT_LE(max_abs(sigma_matrix(s) - tau / PeriSISSM::kCauchyMinJ),
                    1e-12 * tscale / PeriSISSM::kCauchyMinJ);
        }
      }
    }
  }
}

// Finite and continuous at J = 1e-3 (uniaxial collapse diag(1, 1, t), uniform collapse t I),
// and below it sigma = tau / 1e-3 keeps the sign of tau, also for inverted and collapsed F.
TEST(CauchyStress, FiniteAndContinuousAtThreshold)
{
  const double j0 = PeriSISSM::kCauchyMinJ;
  for (const std::string &name : PeriSISSM::material_names()) {
    for (const auto &c : PeriSISSMTest::material_cases()) {
      SCOPED_TRACE(name + " " + c.label);
      const auto m = PeriSISSM::make_material(name, c.mu, c.lambda);
      const double modulus = c.mu + std::abs(c.lambda);
      for (int path = 0; path < 2; ++path) {
        auto F_of_J = [path](double J) -> Matrix3d {
          if (path == 0) return Vector3d(1.0, 1.0, J).asDiagonal();
          return std::cbrt(J) * Matrix3d::Identity();
        };
        double lo[6], hi[6], at[6], Jlo, Jhi, Jat;
        PeriSISSM::cauchy_stress(*m, to_array(F_of_J(j0 * (1.0 - 1e-9))).data(), lo, Jlo);
        PeriSISSM::cauchy_stress(*m, to_array(F_of_J(j0 * (1.0 + 1e-9))).data(), hi, Jhi);
        PeriSISSM::cauchy_stress(*m, to_array(F_of_J(j0)).data(), at, Jat);
        EXPECT_LT(Jlo, j0);
        EXPECT_GT(Jhi, j0);
        // sigma ~ modulus / J0 here; a jump would be of that size, continuity leaves ~1e-9 of it
        // (plus the slope of tau, ~modulus / J0^2 for the neo-Hookean volumetric term, times
        // the 2e-9 J0 step)
        for (int k = 0; k < 6; ++k) {
          EXPECT_NEAR(lo[k], hi[k], 1e-5 * modulus / j0) << "path " << path << " k " << k;
          EXPECT_NEAR(at[k], hi[k], 1e-5 * modulus / j0) << "path " << path << " k " << k;
        }
      }
      const std::vector<Matrix3d> collapsed = {Vector3d(1.0, 1.0, -0.5).asDiagonal(),
                                               Matrix3d::Zero(), -Matrix3d::Identity(),
                                               Vector3d(2.0, 1.0, 0.0).asDiagonal()};
      for (const Matrix3d &F : collapsed) {
        double s[6], J;
        PeriSISSM::cauchy_stress(*m, to_array(F).data(), s, J);
        EXPECT_LE(J, j0);
        const Matrix3d tau = PeriSISSM::first_piola(*m, F) * F.transpose();
        for (double v : s) EXPECT_TRUE(std::isfinite(v));
        EXPECT_LE(max_abs(sigma_matrix(s) - tau / j0), 1e-12 * (max_abs(tau) + modulus) / j0);
      }
    }
  }
}

TEST(VonMises, HydrostaticUniaxialShear)
{
  for (double p : {-3.5e9, 0.0, 1.0, 2.5e-7}) {
    const double hyd[6] = {p, p, p, 0.0, 0.0, 0.0};
    EXPECT_EQ(PeriSISSM::von_mises(hyd), 0.0);
    const double uni[6] = {p, 0.0, 0.0, 0.0, 0.0, 0.0};
    EXPECT_NEAR(PeriSISSM::von_mises(uni), std::abs(p), 1e-15 * std::abs(p));
    const double shear[6] = {0.0, 0.0, 0.0, p, 0.0, 0.0};
    EXPECT_NEAR(PeriSISSM::von_mises(shear), std::sqrt(3.0) * std::abs(p), 1e-15 * std::abs(p));
    // uniaxial + hydrostatic: the hydrostatic part drops out
    const double both[6] = {p + 7.0, 7.0, 7.0, 0.0, 0.0, 0.0};
    EXPECT_NEAR(PeriSISSM::von_mises(both), std::abs(p), 1e-14 * (std::abs(p) + 7.0));
  }
  // invariant under rotation of the stress: a rotated uniaxial stress still gives |sigma|
  std::mt19937_64 rng(37u);
  for (int trial = 0; trial < 50; ++trial) {
    const Matrix3d Q = PeriSISSMTest::random_rotation(rng);
    const double sig = PeriSISSMTest::uniform(rng, -10.0, 10.0);
    const Matrix3d S = Q * Vector3d(sig, 0.0, 0.0).asDiagonal() * Q.transpose();
    const double s[6] = {S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(0, 2), S(1, 2)};
    EXPECT_NEAR(PeriSISSM::von_mises(s), std::abs(sig), 1e-13 * 10.0);
  }
}

// Uniform compression or expansion F = t I (t > 0) of the isotropic models gives a hydrostatic
// Cauchy stress: von Mises zero up to round-off relative to the pressure.
TEST(VonMises, OfHydrostaticCauchyStress)
{
  for (const std::string &name : PeriSISSM::material_names()) {
    const auto m = PeriSISSM::make_material(name, 1.0, 1.5);
    for (double t : {0.5, 0.9, 1.1, 2.0}) {
      double s[6], J;
      PeriSISSM::cauchy_stress(*m, to_array(t * Matrix3d::Identity()).data(), s, J);
      EXPECT_LE(PeriSISSM::von_mises(s), 1e-13 * std::abs(s[0])) << name << " t " << t;
      EXPECT_NE(s[0], 0.0);
    }
  }
}

}    // namespace

// ---------------------------------------------------------------------------------------------
// particle_stress, first_piola: consistency of the per-particle quantities and the small-strain
// limit shared by all models

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using PeriSISSMTest::max_abs;

TEST(ParticleStress, ConsistentWithFirstPiolaAndSplit)
{
  for (const std::string &name : PeriSISSM::material_names()) {
    for (const auto &c : PeriSISSMTest::material_cases()) {
      SCOPED_TRACE(name + " " + c.label);
      const auto m = PeriSISSM::make_material(name, c.mu, c.lambda);
      for (const auto &sample : PeriSISSMTest::random_samples(61u, 30)) {
        const Matrix3d &F = sample.F;
        PeriSISSM::ParticleStress ps;
        PeriSISSM::particle_stress(*m, F, ps, true);
        const PeriSISSM::PrincipalSplit sp = m->split(ps.svd.s);
        const double pscale = max_abs(ps.P) + max_abs(PeriSISSM::implicit_part(ps)) + 1e-300;
        EXPECT_EQ(ps.P, PeriSISSM::first_piola(*m, F));
        EXPECT_EQ(ps.W, PeriSISSMTest::energy_of_F(*m, F));
        EXPECT_NEAR(ps.svd.s.prod(), F.determinant(), 1e-12 * std::pow(F.norm(), 3));
        // Explicit part: P - P^+ = U diag(Phat^-) V^T.
        const Matrix3d Pminus = ps.svd.U * sp.phat_minus.asDiagonal() * ps.svd.V.transpose();
        EXPECT_LE(max_abs(ps.P - PeriSISSM::implicit_part(ps) - Pminus), 1e-13 * pscale);
        // Stiffness direction: symmetric, PSD, and D F = P^+.
        EXPECT_EQ(PeriSISSM::implicit_direction(ps), PeriSISSM::implicit_direction(ps).transpose());
        const double dscale = sp.c.maxCoeff() + 1e-300;
        const Vector3d ev = Eigen::SelfAdjointEigenSolver<Matrix3d>(
                                PeriSISSM::implicit_direction(ps), Eigen::EigenvaluesOnly)
                                .eigenvalues();
        EXPECT_GE(ev.minCoeff(), -1e-14 * dscale);
        EXPECT_LE(max_abs(PeriSISSM::implicit_direction(ps) * F - PeriSISSM::implicit_part(ps)),
                  1e-13 * (max_abs(PeriSISSM::implicit_part(ps)) + dscale * max_abs(F)));
        if (HasFailure()) return;
      }
    }
  }
}

// Corotated linear: c_k = 2 mu + lambda, so the stiffness direction is isotropic (doc/theory.rst).
TEST(ParticleStress, LinearStiffnessIsIsotropic)
{
  const auto m = PeriSISSM::make_material("linear", 1.0, 1.5);
  std::mt19937_64 rng(67u);
  for (int i = 0; i < 100; ++i) {
    PeriSISSM::ParticleStress ps;
    PeriSISSM::particle_stress(*m, PeriSISSMTest::gaussian_matrix(rng), ps, true);
    EXPECT_LE(max_abs(PeriSISSM::implicit_direction(ps) - 3.5 * Matrix3d::Identity()), 1e-14 * 3.5);
  }
}

// Small strain, F = I + e G: every model's P is the linear elastic
// sigma(e G) = 2 mu sym(e G) + lambda tr(e G) I up to O(e^2), so the relative differences
// between models and to sigma are O(e): they shrink ~10x when e does.
TEST(FirstPiola, SmallStrainLimitIsLinearElasticity)
{
  const auto &names = PeriSISSM::material_names();
  std::mt19937_64 rng(71u);
  for (const auto &c : PeriSISSMTest::material_cases()) {
    std::vector<std::unique_ptr<PeriSISSM::Material>> models;
    for (const std::string &name : names)
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

}    // namespace

// The row of compute nosb/atom: Cauchy stress, its von Mises equivalent, J and W of a regular
// particle; a singular one keeps damage and time step with J = 1 and nothing else.
TEST(NosbAtomRow, RegularAndSingularParticles)
{
  using namespace PeriSISSM::NosbAtom;
  const auto m = PeriSISSM::make_material("neohookean", 2.0, 3.0);
  const double F[9] = {1.1, 0.05, 0.0, 0.0, 0.9, 0.02, 0.01, 0.0, 1.05};
  double row[NCOLUMNS], s[6], J;
  PeriSISSM::cauchy_stress(*m, F, s, J);
  PeriSISSM::nosb_atom_row(*m, true, F, 0.75, 0.25, 3.5e-7, row);
  EXPECT_EQ(row[DAMAGE], 0.25);
  EXPECT_EQ(row[ENERGY], 0.75);
  EXPECT_EQ(row[JACOBIAN], J);
  EXPECT_NE(J, 1.0);
  for (int k = 0; k < 6; k++) EXPECT_EQ(row[SXX + k], s[k]);
  EXPECT_EQ(row[VONMISES], PeriSISSM::von_mises(s));
  EXPECT_GT(row[VONMISES], 0.0);
  EXPECT_EQ(row[DTSTABLE], 3.5e-7);
  PeriSISSM::nosb_atom_row(*m, false, F, 0.75, 0.5, 1.0 / 0.0, row);
  const double singular[NCOLUMNS] = {0.5, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0 / 0.0};
  for (int k = 0; k < NCOLUMNS; k++) EXPECT_EQ(row[k], singular[k]) << "column " << k;
}
