// Shared helpers of the contact tests: four points packed as 12 coordinates, seeded random
// configurations, central finite differences of a value and of a gradient.

#ifndef PERISISSM_CONTACT_TEST_HELPERS_H
#define PERISISSM_CONTACT_TEST_HELPERS_H

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <functional>
#include <random>

namespace PeriSISSMContactTest {

using Eigen::Vector3d;
using Points = std::array<Vector3d, 4>;
using X12 = Eigen::Matrix<double, 12, 1>;
using M12 = Eigen::Matrix<double, 12, 12>;

inline X12 pack(const Points &p)
{
  X12 x;
  x << p[0], p[1], p[2], p[3];
  return x;
}

inline Points unpack(const X12 &x)
{
  return {x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9)};
}

inline Vector3d gaussian_point(std::mt19937_64 &rng, double scale = 1.0)
{
  std::normal_distribution<double> n01;
  return scale * Vector3d(n01(rng), n01(rng), n01(rng));
}

inline Points gaussian_points(std::mt19937_64 &rng, double scale = 1.0)
{
  return {gaussian_point(rng, scale), gaussian_point(rng, scale), gaussian_point(rng, scale),
          gaussian_point(rng, scale)};
}

// Central differences of f at x with step h in each coordinate: truncation h^2 f''' / 6,
// round-off about eps |f| / h.
template <int N>
Eigen::Matrix<double, N, 1>
fd_gradient(const std::function<double(const Eigen::Matrix<double, N, 1> &)> &f,
            const Eigen::Matrix<double, N, 1> &x, double h)
{
  Eigen::Matrix<double, N, 1> g;
  for (int i = 0; i < N; i++) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    g(i) = (f(xp) - f(xm)) / (2.0 * h);
  }
  return g;
}

// Central differences of a gradient: column i of the Hessian.
template <int N>
Eigen::Matrix<double, N, N>
fd_hessian(const std::function<Eigen::Matrix<double, N, 1>(const Eigen::Matrix<double, N, 1> &)> &g,
           const Eigen::Matrix<double, N, 1> &x, double h)
{
  Eigen::Matrix<double, N, N> H;
  for (int i = 0; i < N; i++) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    H.col(i) = (g(xp) - g(xm)) / (2.0 * h);
  }
  return H;
}

// max |a - b| / max(max |b|, floor): the error of a derivative relative to its own size (floor
// guards derivatives that vanish).
template <class A, class B> double relative_error(const A &a, const B &b, double floor)
{
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), floor);
}

}    // namespace PeriSISSMContactTest

#endif    // PERISISSM_CONTACT_TEST_HELPERS_H
