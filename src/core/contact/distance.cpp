// Distances between contact primitives and their derivatives (see distance.h).

#include "contact/distance.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace PeriSISSM {

namespace {

  using Eigen::Matrix3d;
  using Eigen::Vector3d;

  // A scalar with its gradient and (when asked) Hessian in N variables.
  template <int N> struct Jet {
    double v = 0.0;
    Eigen::Matrix<double, N, 1> g = Eigen::Matrix<double, N, 1>::Zero();
    Eigen::Matrix<double, N, N> h = Eigen::Matrix<double, N, N>::Zero();
  };

  // [v]_x, the matrix of the cross product: [v]_x u = v x u; [v]_x^T = -[v]_x.
  Matrix3d cross_matrix(const Vector3d &v)
  {
    Matrix3d m;
    m << 0.0, -v(2), v(1), v(2), 0.0, -v(0), -v(1), v(0), 0.0;
    return m;
  }

  // The triple product s = a . (b x c) = det[a, b, c] in the 9 variables (a, b, c).
  // Gradient: ds/da = b x c, ds/db = c x a, ds/dc = a x b.
  // Hessian (constant in each variable, s is trilinear): from ds/da = b x c = -[c]_x b = [b]_x c,
  // d2s/da db = -[c]_x and d2s/da dc = [b]_x; from ds/db = c x a = -[a]_x c, d2s/db dc = -[a]_x;
  // the lower blocks are the transposes, the diagonal blocks zero.
  Jet<9> triple_product(const Vector3d &a, const Vector3d &b, const Vector3d &c, bool hessian)
  {
    Jet<9> j;
    j.v = a.dot(b.cross(c));
    j.g << b.cross(c), c.cross(a), a.cross(b);
    if (hessian) {
      const Matrix3d A = cross_matrix(a), B = cross_matrix(b), C = cross_matrix(c);
      j.h.block<3, 3>(0, 3) = -C;
      j.h.block<3, 3>(0, 6) = B;
      j.h.block<3, 3>(3, 6) = -A;
      j.h.block<3, 3>(3, 0) = C;
      j.h.block<3, 3>(6, 0) = -B;
      j.h.block<3, 3>(6, 3) = A;
    }
    return j;
  }

  // The squared cross product w = |n|^2, n = b x c, in the 6 variables (b, c).
  // dn/db = -[c]_x, dn/dc = [b]_x, so with J = [-[c]_x, [b]_x] (3 x 6): dw = 2 J^T n, i.e.
  // dw/db = 2 [c]_x n = 2 c x n and dw/dc = -2 [b]_x n = 2 n x b.
  // d2w = 2 J^T J + 2 sum_k n_k d2n_k. n is bilinear, n_k = eps_kij b_i c_j, so d2n_k/db_i dc_j =
  // eps_kij and sum_k n_k eps_kij = -([n]_x)_ij: the block d2/db dc gains -2 [n]_x (and the block
  // d2/dc db its transpose, +2 [n]_x); d2n_k/db db = d2n_k/dc dc = 0.
  Jet<6> cross_norm2(const Vector3d &b, const Vector3d &c, bool hessian)
  {
    Jet<6> j;
    const Vector3d n = b.cross(c);
    j.v = n.squaredNorm();
    j.g << 2.0 * c.cross(n), 2.0 * n.cross(b);
    if (hessian) {
      Eigen::Matrix<double, 3, 6> J;
      J << -cross_matrix(c), cross_matrix(b);
      j.h = 2.0 * J.transpose() * J;
      const Matrix3d Nx = cross_matrix(n);
      j.h.block<3, 3>(0, 3) -= 2.0 * Nx;
      j.h.block<3, 3>(3, 0) += 2.0 * Nx;
    }
    return j;
  }

  // |e|^2 in the 3 variables e: gradient 2 e, Hessian 2 I.
  Jet<3> norm2(const Vector3d &e)
  {
    Jet<3> j;
    j.v = e.squaredNorm();
    j.g = 2.0 * e;
    j.h = 2.0 * Matrix3d::Identity();
    return j;
  }

  // A jet in the variables y = L x (L a constant M x N matrix) as a jet in x: g_x = L^T g_y,
  // H_x = L^T H_y L.
  template <int M, int N>
  Jet<N> pull_back(const Jet<M> &j, const Eigen::Matrix<double, M, N> &L, bool hessian)
  {
    Jet<N> out;
    out.v = j.v;
    out.g = L.transpose() * j.g;
    if (hessian) out.h = L.transpose() * j.h * L;
    return out;
  }

  // s^2: gradient 2 s ds, Hessian 2 ds ds^T + 2 s d2s.
  template <int N> Jet<N> square(const Jet<N> &s, bool hessian)
  {
    Jet<N> out;
    out.v = s.v * s.v;
    out.g = 2.0 * s.v * s.g;
    if (hessian) out.h = 2.0 * s.g * s.g.transpose() + 2.0 * s.v * s.h;
    return out;
  }

  // u / w: gradient du / w - u dw / w^2, Hessian
  //   d2u / w - (du dw^T + dw du^T) / w^2 - u d2w / w^2 + 2 u dw dw^T / w^3.
  template <int N> Jet<N> quotient(const Jet<N> &u, const Jet<N> &w, bool hessian)
  {
    Jet<N> out;
    const double iw = 1.0 / w.v;
    out.v = u.v * iw;
    out.g = (u.g - out.v * w.g) * iw;
    if (hessian) {
      const Eigen::Matrix<double, N, N> cross = u.g * w.g.transpose();
      out.h = (u.h - (cross + cross.transpose()) * iw - out.v * w.h +
               2.0 * out.v * iw * w.g * w.g.transpose()) *
          iw;
    }
    return out;
  }

  // The 3 x (3 n) selection of point k minus point l (l < 0: point k alone) among n points.
  template <int N> Eigen::Matrix<double, 3, N> difference(int k, int l)
  {
    Eigen::Matrix<double, 3, N> D = Eigen::Matrix<double, 3, N>::Zero();
    D.template block<3, 3>(0, 3 * k) = Matrix3d::Identity();
    if (l >= 0) D.template block<3, 3>(0, 3 * l) -= Matrix3d::Identity();
    return D;
  }

  // Stacks differences of points into the map L of pull_back.
  template <int N>
  Eigen::Matrix<double, 9, N> stack3(const Eigen::Matrix<double, 3, N> &x,
                                     const Eigen::Matrix<double, 3, N> &y,
                                     const Eigen::Matrix<double, 3, N> &z)
  {
    Eigen::Matrix<double, 9, N> L;
    L << x, y, z;
    return L;
  }

  template <int N>
  Eigen::Matrix<double, 6, N> stack2(const Eigen::Matrix<double, 3, N> &x,
                                     const Eigen::Matrix<double, 3, N> &y)
  {
    Eigen::Matrix<double, 6, N> L;
    L << x, y;
    return L;
  }

  // p p: |p - q|^2 of the difference p - q.
  Jet<6> point_point_jet(const Vector3d &p, const Vector3d &q, bool hessian)
  {
    return pull_back<3, 6>(norm2(p - q), difference<6>(0, 1), hessian);
  }

  // p e0 e1: |(e0 - p) x (e1 - p)|^2 / |e1 - e0|^2 (twice the area of the triangle p e0 e1 over
  // the base, squared).
  Jet<9> point_line_jet(const Vector3d &p, const Vector3d &e0, const Vector3d &e1, bool hessian)
  {
    const Jet<9> num =
        pull_back<6, 9>(cross_norm2(e0 - p, e1 - p, hessian),
                        stack2<9>(difference<9>(1, 0), difference<9>(2, 0)), hessian);
    const Jet<9> den = pull_back<3, 9>(norm2(e1 - e0), difference<9>(2, 1), hessian);
    return quotient(num, den, hessian);
  }

  // p t0 t1 t2: s^2 / w, s = det[p - t0, t1 - t0, t2 - t0] = (p - t0) . n, w = |n|^2.
  Jet<12> point_plane_jet(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                          const Vector3d &t2, bool hessian)
  {
    const Jet<12> s = pull_back<9, 12>(
        triple_product(p - t0, t1 - t0, t2 - t0, hessian),
        stack3<12>(difference<12>(0, 1), difference<12>(2, 1), difference<12>(3, 1)), hessian);
    const Jet<12> w =
        pull_back<6, 12>(cross_norm2(t1 - t0, t2 - t0, hessian),
                         stack2<12>(difference<12>(2, 1), difference<12>(3, 1)), hessian);
    return quotient(square(s, hessian), w, hessian);
  }

  // a0 a1 b0 b1: s^2 / w, s = det[b0 - a0, a1 - a0, b1 - b0] = (b0 - a0) . n, w = |n|^2,
  // n = (a1 - a0) x (b1 - b0).
  Jet<12> line_line_jet(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                        const Vector3d &b1, bool hessian)
  {
    const Jet<12> s = pull_back<9, 12>(
        triple_product(b0 - a0, a1 - a0, b1 - b0, hessian),
        stack3<12>(difference<12>(2, 0), difference<12>(1, 0), difference<12>(3, 2)), hessian);
    const Jet<12> w =
        pull_back<6, 12>(cross_norm2(a1 - a0, b1 - b0, hessian),
                         stack2<12>(difference<12>(1, 0), difference<12>(3, 2)), hessian);
    return quotient(square(s, hessian), w, hessian);
  }

  // A jet of K points (3 K variables) placed among 4 points: slot[k] is where point k goes.
  template <int M, int N>
  void scatter(const Jet<M> &j, const std::array<int, M / 3> &slot, Jet<N> &out)
  {
    out.v = j.v;
    out.g.setZero();
    out.h.setZero();
    for (int a = 0; a < M / 3; a++) {
      out.g.template segment<3>(3 * slot[a]) = j.g.template segment<3>(3 * a);
      for (int b = 0; b < M / 3; b++)
        out.h.template block<3, 3>(3 * slot[a], 3 * slot[b]) =
            j.h.template block<3, 3>(3 * a, 3 * b);
    }
  }

  // The smooth piece of a point-edge pair (p, e0, e1) by class.
  Jet<9> point_edge_jet(const Vector3d &p, const Vector3d &e0, const Vector3d &e1, bool hessian)
  {
    Jet<9> out;
    switch (point_edge_type(p, e0, e1)) {
      case PointEdgeType::kE0:
        scatter<6, 9>(point_point_jet(p, e0, hessian), {0, 1}, out);
        break;
      case PointEdgeType::kE1:
        scatter<6, 9>(point_point_jet(p, e1, hessian), {0, 2}, out);
        break;
      case PointEdgeType::kInterior:
        out = point_line_jet(p, e0, e1, hessian);
        break;
    }
    return out;
  }

  Jet<12> point_triangle_jet(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                             const Vector3d &t2, bool hessian)
  {
    Jet<12> out;
    switch (point_triangle_type(p, t0, t1, t2)) {
      case PointTriangleType::kT0:
        scatter<6, 12>(point_point_jet(p, t0, hessian), {0, 1}, out);
        break;
      case PointTriangleType::kT1:
        scatter<6, 12>(point_point_jet(p, t1, hessian), {0, 2}, out);
        break;
      case PointTriangleType::kT2:
        scatter<6, 12>(point_point_jet(p, t2, hessian), {0, 3}, out);
        break;
      case PointTriangleType::kE01:
        scatter<9, 12>(point_line_jet(p, t0, t1, hessian), {0, 1, 2}, out);
        break;
      case PointTriangleType::kE12:
        scatter<9, 12>(point_line_jet(p, t1, t2, hessian), {0, 2, 3}, out);
        break;
      case PointTriangleType::kE20:
        scatter<9, 12>(point_line_jet(p, t2, t0, hessian), {0, 3, 1}, out);
        break;
      case PointTriangleType::kFace:
        out = point_plane_jet(p, t0, t1, t2, hessian);
        break;
    }
    return out;
  }

  Jet<12> edge_edge_jet(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                        const Vector3d &b1, bool hessian)
  {
    Jet<12> out;
    switch (edge_edge_type(a0, a1, b0, b1)) {
      case EdgeEdgeType::kA0B0:
        scatter<6, 12>(point_point_jet(a0, b0, hessian), {0, 2}, out);
        break;
      case EdgeEdgeType::kA0B1:
        scatter<6, 12>(point_point_jet(a0, b1, hessian), {0, 3}, out);
        break;
      case EdgeEdgeType::kA1B0:
        scatter<6, 12>(point_point_jet(a1, b0, hessian), {1, 2}, out);
        break;
      case EdgeEdgeType::kA1B1:
        scatter<6, 12>(point_point_jet(a1, b1, hessian), {1, 3}, out);
        break;
      case EdgeEdgeType::kA0B:
        scatter<9, 12>(point_line_jet(a0, b0, b1, hessian), {0, 2, 3}, out);
        break;
      case EdgeEdgeType::kA1B:
        scatter<9, 12>(point_line_jet(a1, b0, b1, hessian), {1, 2, 3}, out);
        break;
      case EdgeEdgeType::kAB0:
        scatter<9, 12>(point_line_jet(b0, a0, a1, hessian), {2, 0, 1}, out);
        break;
      case EdgeEdgeType::kAB1:
        scatter<9, 12>(point_line_jet(b1, a0, a1, hessian), {3, 0, 1}, out);
        break;
      case EdgeEdgeType::kInterior:
        out = line_line_jet(a0, a1, b0, b1, hessian);
        break;
    }
    return out;
  }

  // The closest point of the segment e0 e1 to p (parameter clamped to [0, 1]).
  Vector3d closest_on_segment(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
  {
    const Vector3d e = e1 - e0;
    const double ee = e.squaredNorm(), num = (p - e0).dot(e);
    if (!(ee > 0.0) || num <= 0.0) return e0;
    if (num >= ee) return e1;
    return e0 + (num / ee) * e;
  }

  // Edges are "parallel" for the classification when sin^2 of their angle is below this. The
  // line-line formula divides by |u x v|^2 and its distance carries an absolute round-off of
  // about eps_mach |b0 - a0| / sin(angle); classifying a nearly parallel pair by its end points
  // instead overestimates the distance by at most about |u| sin(angle) (the lines' separation
  // changes by that much along the edge). Both are ~1e-8 relative at sin^2 = 1e-16, their balance.
  // Below the mollifier's threshold (sin^2 < 1e-3 at rest shape) the energy is damped anyway.
  constexpr double kParallelSin2 = 1e-16;

  // The interior solution of the segments' closest points: a0 + s u and b0 + t v with
  // s = ((b0 - a0) x v) . n / |n|^2, t = ((b0 - a0) x u) . n / |n|^2, n = u x v (the part of
  // b0 - a0 along n drops out of both). Returns false when parallel or outside either segment.
  bool edge_edge_interior(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                          const Vector3d &b1, double &s, double &t)
  {
    const Vector3d u = a1 - a0, v = b1 - b0, d = b0 - a0, n = u.cross(v);
    const double w = n.squaredNorm();
    if (!(w > kParallelSin2 * u.squaredNorm() * v.squaredNorm())) return false;
    const double sn = d.cross(v).dot(n), tn = d.cross(u).dot(n);
    if (!(sn > 0.0 && sn < w && tn > 0.0 && tn < w)) return false;
    s = sn / w;
    t = tn / w;
    return true;
  }

}    // namespace

// ---- building blocks ----

double point_point_distance2(const Vector3d &p, const Vector3d &q)
{
  return (p - q).squaredNorm();
}

Vector6d point_point_distance2_gradient(const Vector3d &p, const Vector3d &q)
{
  return point_point_jet(p, q, false).g;
}

Matrix6d point_point_distance2_hessian(const Vector3d &p, const Vector3d &q)
{
  return point_point_jet(p, q, true).h;
}

double point_line_distance2(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  return (e0 - p).cross(e1 - p).squaredNorm() / (e1 - e0).squaredNorm();
}

Vector9d point_line_distance2_gradient(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  return point_line_jet(p, e0, e1, false).g;
}

Matrix9d point_line_distance2_hessian(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  return point_line_jet(p, e0, e1, true).h;
}

double point_plane_distance2(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                             const Vector3d &t2)
{
  const Vector3d n = (t1 - t0).cross(t2 - t0);
  const double s = (p - t0).dot(n);
  return s * s / n.squaredNorm();
}

Vector12d point_plane_distance2_gradient(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                         const Vector3d &t2)
{
  return point_plane_jet(p, t0, t1, t2, false).g;
}

Matrix12d point_plane_distance2_hessian(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                        const Vector3d &t2)
{
  return point_plane_jet(p, t0, t1, t2, true).h;
}

double line_line_distance2(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                           const Vector3d &b1)
{
  const Vector3d n = (a1 - a0).cross(b1 - b0);
  const double s = (b0 - a0).dot(n);
  return s * s / n.squaredNorm();
}

Vector12d line_line_distance2_gradient(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                       const Vector3d &b1)
{
  return line_line_jet(a0, a1, b0, b1, false).g;
}

Matrix12d line_line_distance2_hessian(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                      const Vector3d &b1)
{
  return line_line_jet(a0, a1, b0, b1, true).h;
}

// ---- classification ----

PointEdgeType point_edge_type(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  const Vector3d e = e1 - e0;
  const double ee = e.squaredNorm(), num = (p - e0).dot(e);
  if (!(ee > 0.0) || num <= 0.0) return PointEdgeType::kE0;
  if (num >= ee) return PointEdgeType::kE1;
  return PointEdgeType::kInterior;
}

// The face when the projection's barycentric coordinates (signed areas of the sub-triangles
// seen along n, each ((t_j - p) x (t_k - p)) . n, the out-of-plane part of p dropping out) are
// all >= 0; otherwise the closest point is on the boundary, and the nearest of the three
// edges (each with its own point-edge class) decides.
PointTriangleType point_triangle_type(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                      const Vector3d &t2)
{
  const Vector3d n = (t1 - t0).cross(t2 - t0);
  if (n.squaredNorm() > 0.0) {
    const Vector3d q0 = t0 - p, q1 = t1 - p, q2 = t2 - p;
    if (q1.cross(q2).dot(n) >= 0.0 && q2.cross(q0).dot(n) >= 0.0 && q0.cross(q1).dot(n) >= 0.0)
      return PointTriangleType::kFace;
  }
  const Vector3d *t[3] = {&t0, &t1, &t2};
  const PointTriangleType vertex[3] = {PointTriangleType::kT0, PointTriangleType::kT1,
                                       PointTriangleType::kT2};
  const PointTriangleType edge[3] = {PointTriangleType::kE01, PointTriangleType::kE12,
                                     PointTriangleType::kE20};
  PointTriangleType best = PointTriangleType::kT0;
  double best_d2 = INFINITY;
  for (int k = 0; k < 3; k++) {
    const Vector3d &e0 = *t[k], &e1 = *t[(k + 1) % 3];
    const double d2 = (p - closest_on_segment(p, e0, e1)).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      switch (point_edge_type(p, e0, e1)) {
        case PointEdgeType::kE0:
          best = vertex[k];
          break;
        case PointEdgeType::kE1:
          best = vertex[(k + 1) % 3];
          break;
        case PointEdgeType::kInterior:
          best = edge[k];
          break;
      }
    }
  }
  return best;
}

// The minimum of a convex quadratic over the square [0, 1]^2 of the segments' parameters is the
// interior critical point when it lies inside, otherwise on the square's boundary: an end point
// of one segment against the other segment (four point-edge pairs).
EdgeEdgeType edge_edge_type(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                            const Vector3d &b1)
{
  double s, t;
  if (edge_edge_interior(a0, a1, b0, b1, s, t)) return EdgeEdgeType::kInterior;
  struct Candidate {
    const Vector3d &p, &e0, &e1;
    EdgeEdgeType at_e0, at_e1, interior;
  };
  const Candidate cand[4] = {
      {a0, b0, b1, EdgeEdgeType::kA0B0, EdgeEdgeType::kA0B1, EdgeEdgeType::kA0B},
      {a1, b0, b1, EdgeEdgeType::kA1B0, EdgeEdgeType::kA1B1, EdgeEdgeType::kA1B},
      {b0, a0, a1, EdgeEdgeType::kA0B0, EdgeEdgeType::kA1B0, EdgeEdgeType::kAB0},
      {b1, a0, a1, EdgeEdgeType::kA0B1, EdgeEdgeType::kA1B1, EdgeEdgeType::kAB1}};
  EdgeEdgeType best = EdgeEdgeType::kA0B0;
  double best_d2 = INFINITY;
  for (const Candidate &c : cand) {
    const double d2 = (c.p - closest_on_segment(c.p, c.e0, c.e1)).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      switch (point_edge_type(c.p, c.e0, c.e1)) {
        case PointEdgeType::kE0:
          best = c.at_e0;
          break;
        case PointEdgeType::kE1:
          best = c.at_e1;
          break;
        case PointEdgeType::kInterior:
          best = c.interior;
          break;
      }
    }
  }
  return best;
}

// ---- classified distances ----

double point_edge_distance2(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  switch (point_edge_type(p, e0, e1)) {
    case PointEdgeType::kE0:
      return point_point_distance2(p, e0);
    case PointEdgeType::kE1:
      return point_point_distance2(p, e1);
    case PointEdgeType::kInterior:
      break;
  }
  return point_line_distance2(p, e0, e1);
}

Vector9d point_edge_distance2_gradient(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  return point_edge_jet(p, e0, e1, false).g;
}

Matrix9d point_edge_distance2_hessian(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  return point_edge_jet(p, e0, e1, true).h;
}

double point_triangle_distance2(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                                const Vector3d &t2)
{
  switch (point_triangle_type(p, t0, t1, t2)) {
    case PointTriangleType::kT0:
      return point_point_distance2(p, t0);
    case PointTriangleType::kT1:
      return point_point_distance2(p, t1);
    case PointTriangleType::kT2:
      return point_point_distance2(p, t2);
    case PointTriangleType::kE01:
      return point_line_distance2(p, t0, t1);
    case PointTriangleType::kE12:
      return point_line_distance2(p, t1, t2);
    case PointTriangleType::kE20:
      return point_line_distance2(p, t2, t0);
    case PointTriangleType::kFace:
      break;
  }
  return point_plane_distance2(p, t0, t1, t2);
}

Vector12d point_triangle_distance2_gradient(const Vector3d &p, const Vector3d &t0,
                                            const Vector3d &t1, const Vector3d &t2)
{
  return point_triangle_jet(p, t0, t1, t2, false).g;
}

Matrix12d point_triangle_distance2_hessian(const Vector3d &p, const Vector3d &t0,
                                           const Vector3d &t1, const Vector3d &t2)
{
  return point_triangle_jet(p, t0, t1, t2, true).h;
}

double edge_edge_distance2(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                           const Vector3d &b1)
{
  switch (edge_edge_type(a0, a1, b0, b1)) {
    case EdgeEdgeType::kA0B0:
      return point_point_distance2(a0, b0);
    case EdgeEdgeType::kA0B1:
      return point_point_distance2(a0, b1);
    case EdgeEdgeType::kA1B0:
      return point_point_distance2(a1, b0);
    case EdgeEdgeType::kA1B1:
      return point_point_distance2(a1, b1);
    case EdgeEdgeType::kA0B:
      return point_line_distance2(a0, b0, b1);
    case EdgeEdgeType::kA1B:
      return point_line_distance2(a1, b0, b1);
    case EdgeEdgeType::kAB0:
      return point_line_distance2(b0, a0, a1);
    case EdgeEdgeType::kAB1:
      return point_line_distance2(b1, a0, a1);
    case EdgeEdgeType::kInterior:
      break;
  }
  return line_line_distance2(a0, a1, b0, b1);
}

Vector12d edge_edge_distance2_gradient(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                       const Vector3d &b1)
{
  return edge_edge_jet(a0, a1, b0, b1, false).g;
}

Matrix12d edge_edge_distance2_hessian(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                      const Vector3d &b1)
{
  return edge_edge_jet(a0, a1, b0, b1, true).h;
}

// ---- mollifier ----

double edge_edge_mollifier_threshold(const Vector3d &a0_rest, const Vector3d &a1_rest,
                                     const Vector3d &b0_rest, const Vector3d &b1_rest)
{
  return 1e-3 * (a1_rest - a0_rest).squaredNorm() * (b1_rest - b0_rest).squaredNorm();
}

namespace {

  // c = |(a1 - a0) x (b1 - b0)|^2 in the 12 variables.
  Jet<12> parallel_measure(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                           const Vector3d &b1, bool hessian)
  {
    return pull_back<6, 12>(cross_norm2(a1 - a0, b1 - b0, hessian),
                            stack2<12>(difference<12>(1, 0), difference<12>(3, 2)), hessian);
  }

  // e(c) = (2 - c / eps) c / eps = 2 c / eps - c^2 / eps^2 for c < eps: e(eps) = 1,
  // e'(c) = 2 (eps - c) / eps^2 (0 at eps: C1 with the constant 1 beyond), e'' = -2 / eps^2.
  // By the chain rule de = e' dc, d2e = e'' dc dc^T + e' d2c.
  Jet<12> mollifier_jet(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                        const Vector3d &b1, double eps, bool hessian)
  {
    Jet<12> c = parallel_measure(a0, a1, b0, b1, hessian);
    Jet<12> out;
    if (c.v >= eps) {
      out.v = 1.0;
      return out;
    }
    const double r = c.v / eps, d1 = 2.0 * (1.0 - r) / eps, d2 = -2.0 / (eps * eps);
    out.v = (2.0 - r) * r;
    out.g = d1 * c.g;
    if (hessian) out.h = d2 * c.g * c.g.transpose() + d1 * c.h;
    return out;
  }

}    // namespace

double edge_edge_mollifier(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                           const Vector3d &b1, double eps)
{
  const double r = (a1 - a0).cross(b1 - b0).squaredNorm() / eps;
  return r < 1.0 ? (2.0 - r) * r : 1.0;
}

Vector12d edge_edge_mollifier_gradient(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                       const Vector3d &b1, double eps)
{
  return mollifier_jet(a0, a1, b0, b1, eps, false).g;
}

Matrix12d edge_edge_mollifier_hessian(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                                      const Vector3d &b1, double eps)
{
  return mollifier_jet(a0, a1, b0, b1, eps, true).h;
}

// ---- plain distances ----

double point_edge_distance(const Vector3d &p, const Vector3d &e0, const Vector3d &e1)
{
  return (p - closest_on_segment(p, e0, e1)).norm();
}

// Face: |(p - t0) . n| / |n| (the closest point is p minus that along n); otherwise the nearest
// edge's closest point. The classification of point_triangle_type() inlined: outside the face
// the nearest of the three edges' closest points is the distance, whichever vertex or edge it
// is (the same value as through the class, which the continuous collision detection's many
// queries need not know).
double point_triangle_distance(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                               const Vector3d &t2)
{
  const Vector3d n = (t1 - t0).cross(t2 - t0);
  if (n.squaredNorm() > 0.0) {
    const Vector3d q0 = t0 - p, q1 = t1 - p, q2 = t2 - p;
    if (q1.cross(q2).dot(n) >= 0.0 && q2.cross(q0).dot(n) >= 0.0 && q0.cross(q1).dot(n) >= 0.0)
      return std::fabs((p - t0).dot(n)) / n.norm();
  }
  const double d01 = (p - closest_on_segment(p, t0, t1)).squaredNorm();
  const double d12 = (p - closest_on_segment(p, t1, t2)).squaredNorm();
  const double d20 = (p - closest_on_segment(p, t2, t0)).squaredNorm();
  return std::sqrt(std::min(std::min(d01, d12), d20));
}

double edge_edge_distance(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0,
                          const Vector3d &b1)
{
  double s, t;
  if (edge_edge_interior(a0, a1, b0, b1, s, t))
    return ((a0 + s * (a1 - a0)) - (b0 + t * (b1 - b0))).norm();
  return std::min(std::min(point_edge_distance(a0, b0, b1), point_edge_distance(a1, b0, b1)),
                  std::min(point_edge_distance(b0, a0, a1), point_edge_distance(b1, a0, a1)));
}

}    // namespace PeriSISSM
