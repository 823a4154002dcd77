// Shared helpers of the mechanics unit tests: seeded random deformation gradients in named
// families, random rotations, finite differences, and the material parameter sets.

#ifndef PERISISSM_TEST_HELPERS_H
#define PERISISSM_TEST_HELPERS_H

#include "linalg/fast_svd.h"
#include "linalg/signed_svd.h"
#include "materials/material.h"

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace PeriSISSMTest {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Uniform random rotation: normalized Gaussian quaternion.
inline Matrix3d random_rotation(std::mt19937_64 &rng)
{
  std::normal_distribution<double> n01(0.0, 1.0);
  Eigen::Quaterniond q(n01(rng), n01(rng), n01(rng), n01(rng));
  q.normalize();
  return q.toRotationMatrix();
}

inline double uniform(std::mt19937_64 &rng, double lo, double hi)
{
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

inline Matrix3d gaussian_matrix(std::mt19937_64 &rng)
{
  std::normal_distribution<double> n01(0.0, 1.0);
  Matrix3d G;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) G(i, j) = n01(rng);
  return G;
}

// R1 diag(s) R2 with random rotations.
inline Matrix3d rotated_diag(std::mt19937_64 &rng, const Vector3d &s)
{
  return random_rotation(rng) * s.asDiagonal() * random_rotation(rng);
}

enum class Family {
  kNearIdentity,       // I + 1e-3 G
  kGeneral,            // Gaussian entries (either sign of det)
  kNearSingular,       // one singular value +-1e-6, others in [0.5, 2]
  kInverted,           // det < 0: singular values (a, b, -c), c in [0.05, 0.9] min(a, b)
  kStretched,          // singular values 5 * [0.8, 1.2]
  kCompressed,         // singular values 0.05 * [0.8, 1.2]
  kRotationStretch,    // R S, S symmetric positive definite (I + 0.3 sym G, eigenvalues >= 0.2)
};

inline const std::vector<Family> &all_families()
{
  static const std::vector<Family> f = {
      Family::kNearIdentity, Family::kGeneral,    Family::kNearSingular,   Family::kInverted,
      Family::kStretched,    Family::kCompressed, Family::kRotationStretch};
  return f;
}

inline const char *family_name(Family f)
{
  switch (f) {
    case Family::kNearIdentity:
      return "near-identity";
    case Family::kGeneral:
      return "general";
    case Family::kNearSingular:
      return "near-singular";
    case Family::kInverted:
      return "inverted";
    case Family::kStretched:
      return "stretched x5";
    case Family::kCompressed:
      return "compressed x0.05";
    case Family::kRotationStretch:
      return "rotation*stretch";
  }
  return "?";
}

// Corotated models have a kink where an inverted F has |s_2| = |s_3| (material_linear.h); keep
// random F at least 1% of |s_1| away from it so that finite differences see a smooth W.
inline bool near_corotated_kink(const Matrix3d &F)
{
  const Vector3d s = PeriSISSM::signed_svd(F).s;
  return s(2) < 0.0 && std::abs(s(1)) - std::abs(s(2)) < 1e-2 * std::abs(s(0));
}

inline Matrix3d random_F(Family family, std::mt19937_64 &rng)
{
  switch (family) {
    case Family::kNearIdentity:
      return Matrix3d::Identity() + 1e-3 * gaussian_matrix(rng);
    case Family::kGeneral: {
      Matrix3d F;
      do {
        F = gaussian_matrix(rng);
      } while (near_corotated_kink(F));
      return F;
    }
    case Family::kNearSingular: {
      const double sign = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
      return rotated_diag(rng,
                          Vector3d(uniform(rng, 0.5, 2.0), uniform(rng, 0.5, 2.0), sign * 1e-6));
    }
    case Family::kInverted: {
      const double a = uniform(rng, 0.5, 2.0);
      const double b = uniform(rng, 0.5, 2.0);
      const double c = uniform(rng, 0.05, 0.9) * std::min(a, b);
      return rotated_diag(rng, Vector3d(a, b, -c));
    }
    case Family::kStretched:
      return rotated_diag(
          rng,
          5.0 * Vector3d(uniform(rng, 0.8, 1.2), uniform(rng, 0.8, 1.2), uniform(rng, 0.8, 1.2)));
    case Family::kCompressed:
      return rotated_diag(
          rng,
          0.05 * Vector3d(uniform(rng, 0.8, 1.2), uniform(rng, 0.8, 1.2), uniform(rng, 0.8, 1.2)));
    case Family::kRotationStretch: {
      Matrix3d S;
      do {
        const Matrix3d G = gaussian_matrix(rng);
        S = Matrix3d::Identity() + 0.15 * (G + G.transpose());
      } while (S.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() < 0.2);
      return random_rotation(rng) * S;
    }
  }
  return Matrix3d::Identity();
}

struct Sample {
  Family family;
  Matrix3d F;
};

// per_family F of every family from a seeded generator (7 families: 150 each gives 1050).
inline std::vector<Sample> random_samples(unsigned seed, int per_family = 150)
{
  std::mt19937_64 rng(seed);
  std::vector<Sample> out;
  for (Family f : all_families())
    for (int i = 0; i < per_family; ++i) out.push_back({f, random_F(f, rng)});
  return out;
}

// W(F) through the signed SVD the force evaluation uses (fast_signed_svd: particle_stress()
// and this agree to the last bit; the reference signed_svd() agrees to round-off).
inline double energy_of_F(const PeriSISSM::Material &m, const Matrix3d &F)
{
  return m.energy(PeriSISSM::fast_signed_svd(F).s);
}

// Central finite-difference gradient dW/dF with step h in every entry.
inline Matrix3d fd_gradient(const std::function<double(const Matrix3d &)> &W, const Matrix3d &F,
                            double h)
{
  Matrix3d g;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Matrix3d Fp = F, Fm = F;
      Fp(i, j) += h;
      Fm(i, j) -= h;
      g(i, j) = (W(Fp) - W(Fm)) / (2.0 * h);
    }
  }
  return g;
}

// Central difference (f(x + h d) - f(x - h d)) / (2 h) of a function of the coordinates x along
// the direction d (as many entries as x); for a vector-valued f, entry by entry.
inline double central_difference(const std::function<double(const std::vector<double> &)> &f,
                                 const std::vector<double> &x, const std::vector<double> &d,
                                 double h)
{
  std::vector<double> xp = x, xm = x;
  for (size_t k = 0; k < x.size(); ++k) {
    xp[k] += h * d[k];
    xm[k] -= h * d[k];
  }
  return (f(xp) - f(xm)) / (2.0 * h);
}

inline std::vector<double>
central_differences(const std::function<std::vector<double>(const std::vector<double> &)> &f,
                    const std::vector<double> &x, const std::vector<double> &d, double h)
{
  std::vector<double> xp = x, xm = x;
  for (size_t k = 0; k < x.size(); ++k) {
    xp[k] += h * d[k];
    xm[k] -= h * d[k];
  }
  std::vector<double> df = f(xp);
  const std::vector<double> fm = f(xm);
  for (size_t k = 0; k < df.size(); ++k) df[k] = (df[k] - fm[k]) / (2.0 * h);
  return df;
}

// The direction of coordinate k among n.
inline std::vector<double> unit_direction(size_t n, size_t k)
{
  std::vector<double> d(n, 0.0);
  d[k] = 1.0;
  return d;
}

// Material parameter sets: Poisson's ratio 0.3, 0 (lambda = 0), 0.49 (nearly incompressible),
// -0.3 (lambda < 0), and steel-like magnitudes (K = 160 GPa, G = 79 GPa).
struct MaterialCase {
  std::string label;
  double mu;
  double lambda;
};

inline const std::vector<MaterialCase> &material_cases()
{
  static const std::vector<MaterialCase> cases = {
      {"nu0p3", 1.0, 1.5},
      {"nu0", 1.0, 0.0},
      {"nu0p49", 1.0, 49.0},
      {"nuMinus0p3", 1.0, -0.375},
      {"steel", 79e9, 160e9 - 2.0 * 79e9 / 3.0},
  };
  return cases;
}

// Readable test names in gtest/ctest output.
inline void PrintTo(const MaterialCase &c, std::ostream *os)
{
  *os << c.label << " (mu " << c.mu << ", lambda " << c.lambda << ")";
}

inline double max_abs(const Matrix3d &A)
{
  return A.cwiseAbs().maxCoeff();
}

}    // namespace PeriSISSMTest

#endif    // PERISISSM_TEST_HELPERS_H
