// Lagged smooth friction of barrier pairs (see friction.h).

#include "contact/friction.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

using Eigen::Vector3d;

// ---- scalar mollifier ----

// f0(y) = y^2 (1 - y / (3 eps)) / eps + eps / 3 below eps: f0' = 2 y / eps - y^2 / eps^2 = f1.
double friction_f0(double y, double eps)
{
  if (y >= eps) return y;
  return y * y * (1.0 - y / (3.0 * eps)) / eps + eps / 3.0;
}

double friction_f1(double y, double eps)
{
  if (y >= eps) return 1.0;
  return y * (2.0 - y / eps) / eps;
}

// f1' = 2 / eps - 2 y / eps^2 = 2 (1 - y / eps) / eps, 0 at and beyond eps.
double friction_f1_derivative(double y, double eps)
{
  if (y >= eps) return 0.0;
  return 2.0 * (1.0 - y / eps) / eps;
}

// f1 / y = (2 - y / eps) / eps below eps (2 / eps at y = 0, no division), 1 / y beyond.
double friction_f1_over_y(double y, double eps)
{
  if (y >= eps) return 1.0 / y;
  return (2.0 - y / eps) / eps;
}

// ---- lagged data ----

Eigen::Matrix<double, 3, 2> tangent_basis(const Vector3d &n)
{
  // the coordinate axis least aligned with n, made orthogonal to it
  int k = 0;
  n.cwiseAbs().minCoeff(&k);
  const Vector3d t0 = (Vector3d::Unit(k) - n(k) * n).normalized();
  Eigen::Matrix<double, 3, 2> T;
  T << t0, n.cross(t0);
  return T;
}

namespace {

  using Points4 = std::array<Vector3d, 4>;

  // Parameter of the closest point of the segment e0 e1 to p, clamped to [0, 1] as
  // point_edge_type() clamps it (0 for a segment of zero length).
  double segment_parameter(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
  {
    const Vector3d e = e1 - e0;
    const double ee = e.squaredNorm();
    if (!(ee > 0.0)) return 0.0;
    return std::min(1.0, std::max(0.0, (p - e0).dot(e) / ee));
  }

  // The pair's data from its points, the signed weights of its classified closest points, its
  // squared distance D (the barrier's, distance.h) and mollifier e, and the plane normal m of its
  // primitives (triangle normal, edges' cross product; 0 if none). Normal: for a point over the
  // face or two edges' interiors (flat), m turned to the side of r = sum w_i x_i (r is parallel
  // to m there, but m carries no cancellation as r -> 0); otherwise r / |r|; m when r = 0.
  // lambda = kappa e |b'(sqrt(D) - dmin)| within reach.
  FrictionPair make_pair(const Points4 &x, int count, const std::array<double, 4> &w, double D,
                         double e, const Vector3d &m, bool flat, const BarrierParameters &prm)
  {
    FrictionPair pair;
    pair.count = count;
    pair.w = w;
    Vector3d r = Vector3d::Zero();
    for (int i = 0; i < count; i++) r += w[i] * x[i];
    const double rn = r.norm(), mn = m.norm();
    if (flat && mn > 0.0)
      pair.normal = (r.dot(m) < 0.0 ? -m : m) / mn;
    else if (rn > 0.0)
      pair.normal = r / rn;
    else if (mn > 0.0)
      pair.normal = m / mn;
    pair.T = tangent_basis(pair.normal);
    const double d = std::sqrt(D), reach = prm.dmin + prm.dhat;
    if (d < reach)
      pair.lambda = prm.kappa * e * std::fabs(barrier_first_derivative(d - prm.dmin, prm.dhat));
    return pair;
  }

}    // namespace

// Weights (1, -b0, -b1, -b2), b the barycentric coordinates of the triangle's closest point:
// the projection's for the face (signed areas over |n|^2, as point_triangle_type() computes
// them), a segment's parameter for an edge, a 1 for a vertex.
FrictionPair point_triangle_friction_pair(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                          const Vector3d &t2, const BarrierParameters &prm)
{
  const Vector3d n = (t1 - t0).cross(t2 - t0);
  std::array<double, 4> w{1.0, 0.0, 0.0, 0.0};
  const PointTriangleType type = point_triangle_type(p, t0, t1, t2);
  switch (type) {
    case PointTriangleType::kT0:
      w[1] = -1.0;
      break;
    case PointTriangleType::kT1:
      w[2] = -1.0;
      break;
    case PointTriangleType::kT2:
      w[3] = -1.0;
      break;
    case PointTriangleType::kE01: {
      const double s = segment_parameter(p, t0, t1);
      w[1] = -(1.0 - s);
      w[2] = -s;
      break;
    }
    case PointTriangleType::kE12: {
      const double s = segment_parameter(p, t1, t2);
      w[2] = -(1.0 - s);
      w[3] = -s;
      break;
    }
    case PointTriangleType::kE20: {
      const double s = segment_parameter(p, t2, t0);
      w[3] = -(1.0 - s);
      w[1] = -s;
      break;
    }
    case PointTriangleType::kFace: {
      const double nn = n.squaredNorm();
      w[1] = -(t1 - p).cross(t2 - p).dot(n) / nn;
      w[2] = -(t2 - p).cross(t0 - p).dot(n) / nn;
      w[3] = -1.0 - w[1] - w[2];
      break;
    }
  }
  return make_pair({p, t0, t1, t2}, 4, w, point_triangle_distance2(p, t0, t1, t2), 1.0, n,
                   type == PointTriangleType::kFace, prm);
}

// Weights (1 - s, s, -(1 - t), -t) of the closest points a0 + s (a1 - a0) and b0 + t (b1 - b0).
// Interior: s = ((b0 - a0) x v) . n / |n|^2, t = ((b0 - a0) x u) . n / |n|^2, n = u x v (the
// stationarity of |a0 + s u - b0 - t v|^2 in s and t, solved by Cramer's rule).
FrictionPair edge_edge_friction_pair(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                     const Vector3d &b1, double eps, const BarrierParameters &prm)
{
  const Vector3d u = a1 - a0, v = b1 - b0, n = u.cross(v);
  double s = 0.0, t = 0.0;
  const EdgeEdgeType type = edge_edge_type(a0, a1, b0, b1);
  switch (type) {
    case EdgeEdgeType::kA0B0:
      break;
    case EdgeEdgeType::kA0B1:
      t = 1.0;
      break;
    case EdgeEdgeType::kA1B0:
      s = 1.0;
      break;
    case EdgeEdgeType::kA1B1:
      s = t = 1.0;
      break;
    case EdgeEdgeType::kA0B:
      t = segment_parameter(a0, b0, b1);
      break;
    case EdgeEdgeType::kA1B:
      s = 1.0;
      t = segment_parameter(a1, b0, b1);
      break;
    case EdgeEdgeType::kAB0:
      s = segment_parameter(b0, a0, a1);
      break;
    case EdgeEdgeType::kAB1:
      t = 1.0;
      s = segment_parameter(b1, a0, a1);
      break;
    case EdgeEdgeType::kInterior: {
      const Vector3d d = b0 - a0;
      const double nn = n.squaredNorm();
      s = d.cross(v).dot(n) / nn;
      t = d.cross(u).dot(n) / nn;
      break;
    }
  }
  const double D = edge_edge_distance2(a0, a1, b0, b1);
  const double e = edge_edge_mollifier(a0, a1, b0, b1, eps);
  return make_pair({a0, a1, b0, b1}, 4, {1.0 - s, s, -(1.0 - t), -t}, D, e, n,
                   type == EdgeEdgeType::kInterior, prm);
}

FrictionPair point_point_friction_pair(const Vector3d &p, const Vector3d &q,
                                       const BarrierParameters &prm)
{
  return make_pair({p, q, Vector3d::Zero(), Vector3d::Zero()}, 2, {1.0, -1.0, 0.0, 0.0},
                   point_point_distance2(p, q), 1.0, Vector3d::Zero(), false, prm);
}

// ---- friction potential ----

Eigen::Vector2d tangential_displacement(const FrictionPair &pair, const Vector12d &u)
{
  Vector3d r = Vector3d::Zero();
  for (int i = 0; i < pair.count; i++) r += pair.w[i] * u.segment<3>(3 * i);
  return pair.T.transpose() * r;
}

double friction_energy(const FrictionPair &pair, const Vector12d &u, const FrictionParameters &prm)
{
  const double y = tangential_displacement(pair, u).norm();
  return prm.mu * pair.lambda * friction_f0(y, prm.slip_length);
}

// dD/du_i = mu lambda w_i (f1(y) / y) T u_T.
Vector12d friction_gradient(const FrictionPair &pair, const Vector12d &u,
                            const FrictionParameters &prm)
{
  const Eigen::Vector2d uT = tangential_displacement(pair, u);
  const Vector3d f =
      prm.mu * pair.lambda * friction_f1_over_y(uT.norm(), prm.slip_length) * (pair.T * uT);
  Vector12d g = Vector12d::Zero();
  for (int i = 0; i < pair.count; i++) g.segment<3>(3 * i) = pair.w[i] * f;
  return g;
}

// d2D/du_i du_j = mu lambda w_i w_j T M T^T, M = a (I - q q^T) + b q q^T with a = f1 / y and
// b = f1' clamped at 0 (both 2 / eps at y = 0, where M = (2 / eps) I).
Matrix12d friction_hessian(const FrictionPair &pair, const Vector12d &u,
                           const FrictionParameters &prm)
{
  const Eigen::Vector2d uT = tangential_displacement(pair, u);
  const double y = uT.norm(), eps = prm.slip_length;
  const double a = friction_f1_over_y(y, eps);
  const double b = std::max(0.0, friction_f1_derivative(y, eps));
  Eigen::Matrix2d M = a * Eigen::Matrix2d::Identity();
  if (y > 0.0) {
    const Eigen::Vector2d q = uT / y;
    M += (b - a) * q * q.transpose();
  }
  const Eigen::Matrix3d K = prm.mu * pair.lambda * pair.T * M * pair.T.transpose();
  Matrix12d H = Matrix12d::Zero();
  for (int i = 0; i < pair.count; i++)
    for (int j = 0; j < pair.count; j++) H.block<3, 3>(3 * i, 3 * j) = pair.w[i] * pair.w[j] * K;
  return H;
}

}    // namespace PeriSISSM
