// The contact barrier and the pair energies built on it (see barrier.h).

#include "contact/barrier.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

using Eigen::Vector3d;

// ---- scalar barrier ----

// b(g) = -(g - dhat)^2 ln(g / dhat).
double barrier(double g, double dhat)
{
  if (g >= dhat) return 0.0;
  if (g <= 0.0) return INFINITY;
  const double r = g - dhat;
  return -r * r * std::log(g / dhat);
}

// b'(g) = -2 (g - dhat) ln(g / dhat) - (g - dhat)^2 / g
//       = (dhat - g) (2 ln(g / dhat) - dhat / g + 1).
double barrier_first_derivative(double g, double dhat)
{
  if (g >= dhat) return 0.0;
  if (g <= 0.0) return -INFINITY;
  return (dhat - g) * (2.0 * std::log(g / dhat) - dhat / g + 1.0);
}

// b''(g) = d/dg [-2 (g - dhat) ln(g / dhat) - (g - dhat)^2 / g]
//        = -2 ln(g / dhat) - 2 (g - dhat) / g - 2 (g - dhat) / g + (g - dhat)^2 / g^2
//        = -2 ln(g / dhat) - 4 (g - dhat) / g + (g - dhat)^2 / g^2   (0 at g = dhat).
double barrier_second_derivative(double g, double dhat)
{
  if (g >= dhat) return 0.0;
  if (g <= 0.0) return INFINITY;
  const double q = (g - dhat) / g;
  return -2.0 * std::log(g / dhat) - 4.0 * q + q * q;
}

// ---- barrier of the squared distance ----

// B(D) = b(d - dmin), d = sqrt(D); dd/dD = 1 / (2 d), d2d/dD2 = -1 / (4 d^3), so
// B' = b' / (2 d) and B'' = b'' / (4 d^2) - b' / (4 d^3).
double distance_barrier(double D, double dmin, double dhat)
{
  return barrier(std::sqrt(D) - dmin, dhat);
}

double distance_barrier_first_derivative(double D, double dmin, double dhat)
{
  const double d = std::sqrt(D);
  if (d - dmin >= dhat) return 0.0;
  return barrier_first_derivative(d - dmin, dhat) / (2.0 * d);
}

double distance_barrier_second_derivative(double D, double dmin, double dhat)
{
  const double d = std::sqrt(D);
  if (d - dmin >= dhat) return 0.0;
  const double g = d - dmin;
  return barrier_second_derivative(g, dhat) / (4.0 * D) -
      barrier_first_derivative(g, dhat) / (4.0 * D * d);
}

// ---- pair energies ----

namespace {

  // True when a squared distance D is within the barrier's reach, dmin + dhat.
  bool acts(double D, const BarrierParameters &prm)
  {
    const double reach = prm.dmin + prm.dhat;
    return D < reach * reach;
  }

  // kappa B(D(x)) from the distance's gradient and Hessian: gradient kappa B' dD, Hessian
  // kappa (B'' dD dD^T + B' d2D).
  template <int N>
  Eigen::Matrix<double, N, N> composed_hessian(double D, const Eigen::Matrix<double, N, 1> &dD,
                                               const Eigen::Matrix<double, N, N> &d2D,
                                               const BarrierParameters &prm)
  {
    const double b1 = distance_barrier_first_derivative(D, prm.dmin, prm.dhat);
    const double b2 = distance_barrier_second_derivative(D, prm.dmin, prm.dhat);
    return prm.kappa * (b2 * dD * dD.transpose() + b1 * d2D);
  }

  template <int N> Eigen::Matrix<double, N, N> psd(const Eigen::Matrix<double, N, N> &H)
  {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(H);
    const Eigen::Matrix<double, N, 1> lambda = eig.eigenvalues().cwiseMax(0.0);
    return eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
  }

}    // namespace

Matrix12d project_to_psd(const Matrix12d &H)
{
  return psd<12>(H);
}
Matrix6d project_to_psd(const Matrix6d &H)
{
  return psd<6>(H);
}

double point_triangle_barrier_energy(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                     const Vector3d &t2, const BarrierParameters &prm)
{
  const double D = point_triangle_distance2(p, t0, t1, t2);
  return acts(D, prm) ? prm.kappa * distance_barrier(D, prm.dmin, prm.dhat) : 0.0;
}

Vector12d point_triangle_barrier_gradient(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                          const Vector3d &t2, const BarrierParameters &prm)
{
  Vector12d g;
  point_triangle_barrier(p, t0, t1, t2, point_triangle_distance2(p, t0, t1, t2), prm, g);
  return g;
}

double point_triangle_barrier(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                              const Vector3d &t2, double D, const BarrierParameters &prm,
                              Vector12d &g)
{
  if (!acts(D, prm)) {
    g.setZero();
    return 0.0;
  }
  g = prm.kappa * distance_barrier_first_derivative(D, prm.dmin, prm.dhat) *
      point_triangle_distance2_gradient(p, t0, t1, t2);
  return prm.kappa * distance_barrier(D, prm.dmin, prm.dhat);
}

Matrix12d point_triangle_barrier_hessian(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                         const Vector3d &t2, const BarrierParameters &prm,
                                         bool project_psd)
{
  const double D = point_triangle_distance2(p, t0, t1, t2);
  if (!acts(D, prm)) return Matrix12d::Zero();
  const Matrix12d H = composed_hessian<12>(D, point_triangle_distance2_gradient(p, t0, t1, t2),
                                           point_triangle_distance2_hessian(p, t0, t1, t2), prm);
  return project_psd ? psd<12>(H) : H;
}

// E = kappa e B with e the mollifier (1 unless nearly parallel):
//   dE = kappa (B de + e dB),
//   d2E = kappa (B d2e + de dB^T + dB de^T + e d2B),  dB = B' dD, d2B = B'' dD dD^T + B' d2D.
double edge_edge_barrier_energy(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                const Vector3d &b1, double eps, const BarrierParameters &prm)
{
  const double D = edge_edge_distance2(a0, a1, b0, b1);
  if (!acts(D, prm)) return 0.0;
  return prm.kappa * edge_edge_mollifier(a0, a1, b0, b1, eps) *
      distance_barrier(D, prm.dmin, prm.dhat);
}

Vector12d edge_edge_barrier_gradient(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                     const Vector3d &b1, double eps, const BarrierParameters &prm)
{
  Vector12d g;
  edge_edge_barrier(a0, a1, b0, b1, eps, edge_edge_distance2(a0, a1, b0, b1), prm, g);
  return g;
}

double edge_edge_barrier(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                         const Vector3d &b1, double eps, double D, const BarrierParameters &prm,
                         Vector12d &g)
{
  if (!acts(D, prm)) {
    g.setZero();
    return 0.0;
  }
  const double B = distance_barrier(D, prm.dmin, prm.dhat);
  const double B1 = distance_barrier_first_derivative(D, prm.dmin, prm.dhat);
  const double e = edge_edge_mollifier(a0, a1, b0, b1, eps);
  g = e * B1 * edge_edge_distance2_gradient(a0, a1, b0, b1);
  if (e < 1.0) g += B * edge_edge_mollifier_gradient(a0, a1, b0, b1, eps);
  g = prm.kappa * g;
  return prm.kappa * e * B;
}

Matrix12d edge_edge_barrier_hessian(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                    const Vector3d &b1, double eps, const BarrierParameters &prm,
                                    bool project_psd)
{
  const double D = edge_edge_distance2(a0, a1, b0, b1);
  if (!acts(D, prm)) return Matrix12d::Zero();
  const Vector12d dD = edge_edge_distance2_gradient(a0, a1, b0, b1);
  const Matrix12d d2B = composed_hessian<12>(D, dD, edge_edge_distance2_hessian(a0, a1, b0, b1),
                                             prm);    // kappa d2B
  const double e = edge_edge_mollifier(a0, a1, b0, b1, eps);
  Matrix12d H = e * d2B;
  if (e < 1.0) {
    const double B = distance_barrier(D, prm.dmin, prm.dhat);
    const Vector12d dB = distance_barrier_first_derivative(D, prm.dmin, prm.dhat) * dD;
    const Vector12d de = edge_edge_mollifier_gradient(a0, a1, b0, b1, eps);
    H += prm.kappa *
        (B * edge_edge_mollifier_hessian(a0, a1, b0, b1, eps) + de * dB.transpose() +
         dB * de.transpose());
  }
  return project_psd ? psd<12>(H) : H;
}

double point_point_barrier_energy(const Vector3d &p, const Vector3d &q,
                                  const BarrierParameters &prm)
{
  const double D = point_point_distance2(p, q);
  return acts(D, prm) ? prm.kappa * distance_barrier(D, prm.dmin, prm.dhat) : 0.0;
}

Vector6d point_point_barrier_gradient(const Vector3d &p, const Vector3d &q,
                                      const BarrierParameters &prm)
{
  Vector6d g;
  point_point_barrier(p, q, point_point_distance2(p, q), prm, g);
  return g;
}

double point_point_barrier(const Vector3d &p, const Vector3d &q, double D,
                           const BarrierParameters &prm, Vector6d &g)
{
  if (!acts(D, prm)) {
    g.setZero();
    return 0.0;
  }
  g = prm.kappa * distance_barrier_first_derivative(D, prm.dmin, prm.dhat) *
      point_point_distance2_gradient(p, q);
  return prm.kappa * distance_barrier(D, prm.dmin, prm.dhat);
}

Matrix6d point_point_barrier_hessian(const Vector3d &p, const Vector3d &q,
                                     const BarrierParameters &prm, bool project_psd)
{
  const double D = point_point_distance2(p, q);
  if (!acts(D, prm)) return Matrix6d::Zero();
  const Matrix6d H = composed_hessian<6>(D, point_point_distance2_gradient(p, q),
                                         point_point_distance2_hessian(p, q), prm);
  return project_psd ? psd<6>(H) : H;
}

// ---- barrier stiffness ----

double initial_barrier_stiffness(double bbox_diagonal, double dhat, double average_mass,
                                 double energy_dot_barrier, double barrier_dot_barrier,
                                 double &kappa_max)
{
  const double g0 = std::min(1e-8 * bbox_diagonal, 0.5 * dhat);
  const double kappa_min = 1e11 * average_mass / barrier_second_derivative(g0, dhat);
  kappa_max = 100.0 * kappa_min;
  if (!(barrier_dot_barrier > 0.0)) return kappa_min;
  const double kappa = -energy_dot_barrier / barrier_dot_barrier;
  return std::min(kappa_max, std::max(kappa_min, kappa));
}

double update_barrier_stiffness(double previous_min_gap, double min_gap, double kappa_max,
                                double kappa, double bbox_diagonal)
{
  const double small = 1e-9 * bbox_diagonal;
  if (previous_min_gap < small && min_gap < small && min_gap < previous_min_gap)
    return std::min(kappa_max, 2.0 * kappa);
  return kappa;
}

}    // namespace PeriSISSM
