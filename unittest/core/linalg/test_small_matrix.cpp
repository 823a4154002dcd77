// 3x3 solves and rotations (linalg/small_matrix.h).

#include "linalg/small_matrix.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace {

// Random SPD and general systems: residual at round-off times the condition number; a singular
// general matrix is refused and leaves x untouched.
TEST(SmallMatrix, SolvesAndRefusesSingular)
{
  std::mt19937_64 rng(2u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 200; t++) {
    Eigen::Matrix3d G;
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) G(a, b) = u(rng);
    const Eigen::Matrix3d S = G * G.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    const double D[6] = {S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(0, 2), S(1, 2)};
    const double r[3] = {u(rng), u(rng), u(rng)};
    double d[3];
    PeriSISSM::solve_spd3(D, r, d);
    const Eigen::Vector3d res =
        S * Eigen::Vector3d(d[0], d[1], d[2]) - Eigen::Vector3d(r[0], r[1], r[2]);
    const double cond = S.norm() * S.inverse().norm();
    EXPECT_LE(res.norm(),
              1e-14 * cond * S.norm() * Eigen::Vector3d(d[0], d[1], d[2]).norm() + 1e-15);
    double M[9], x[3] = {7, 7, 7};
    for (int q = 0; q < 9; q++) M[q] = G(q / 3, q % 3);
    ASSERT_TRUE(PeriSISSM::solve3(M, r, 0.0, x));
    const Eigen::Vector3d res2 =
        G * Eigen::Vector3d(x[0], x[1], x[2]) - Eigen::Vector3d(r[0], r[1], r[2]);
    EXPECT_LE(res2.norm(),
              1e-12 * G.norm() * G.inverse().norm() *
                  (1.0 + Eigen::Vector3d(x[0], x[1], x[2]).norm()));
  }
  const double sing[9] = {1, 2, 3, 2, 4, 6, 0, 1, 1};
  const double r[3] = {1, 1, 1};
  double x[3] = {7, 7, 7};
  EXPECT_FALSE(PeriSISSM::solve3(sing, r, 1e-12, x));
  EXPECT_EQ(x[0], 7.0);
}

// rotate3 agrees with Eigen's angle-axis rotation and keeps lengths.
TEST(SmallMatrix, RotationMatchesAngleAxis)
{
  std::mt19937_64 rng(4u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 100; t++) {
    Eigen::Vector3d k(u(rng), u(rng), u(rng));
    k.normalize();
    const double angle = 3.0 * u(rng);
    Eigen::Vector3d r(u(rng), u(rng), u(rng));
    const Eigen::Vector3d expect = Eigen::AngleAxisd(angle, k) * r;
    double rr[3] = {r(0), r(1), r(2)};
    PeriSISSM::rotate3(k.data(), std::cos(angle), std::sin(angle), rr);
    EXPECT_LE((Eigen::Vector3d(rr[0], rr[1], rr[2]) - expect).norm(), 1e-15 * 8);
  }
}

}    // namespace
