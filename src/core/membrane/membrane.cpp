// The correspondence of a membrane particle (see membrane.h).

#include "membrane/membrane.h"

#include "linalg/small_matrix.h"
#include "materials/material.h"
#include "peri/family.h"
#include "peri/particle.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

namespace {

  using RowMatrix3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

  inline double dot(const double a[3], const double b[3])
  {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }

  // y = A x for row-major A
  inline void apply(const double A[9], const double x[3], double y[3])
  {
    for (int r = 0; r < 3; r++) y[r] = A[3 * r] * x[0] + A[3 * r + 1] * x[1] + A[3 * r + 2] * x[2];
  }

  // v scaled to unit length; false (v unchanged) when it has none
  inline bool normalize(double v[3])
  {
    const double l = std::sqrt(dot(v, v));
    if (!(l > 0.0)) return false;
    for (int k = 0; k < 3; k++) v[k] /= l;
    return true;
  }

  // Closed-form SVD of a 2x2 matrix m = R(phi) diag(s1, s2) R(theta), R(x) the rotation by x,
  // s1 >= |s2|, s2 < 0 only when det m < 0 (Blinn's construction from the matrix's conformal and
  // anti-conformal parts).
  struct SVD2 {
    double s1, s2, cphi, sphi, ctheta, stheta;
  };

  SVD2 svd2(double m00, double m01, double m10, double m11)
  {
    const double e = 0.5 * (m00 + m11), f = 0.5 * (m00 - m11);
    const double g = 0.5 * (m10 + m01), h = 0.5 * (m10 - m01);
    const double q = std::hypot(e, h), r = std::hypot(f, g);
    const double a1 = std::atan2(g, f), a2 = std::atan2(h, e);
    const double theta = 0.5 * (a2 - a1), phi = 0.5 * (a2 + a1);
    return {q + r, q - r, std::cos(phi), std::sin(phi), std::cos(theta), std::sin(theta)};
  }

}    // namespace

void tangent_frame(const double n0[3], double t1[3], double t2[3])
{
  // the coordinate axis least aligned with n0, made orthogonal to it
  int axis = 0;
  if (std::fabs(n0[1]) < std::fabs(n0[axis])) axis = 1;
  if (std::fabs(n0[2]) < std::fabs(n0[axis])) axis = 2;
  const double along = n0[axis];
  for (int k = 0; k < 3; k++) t1[k] = (k == axis ? 1.0 : 0.0) - along * n0[k];
  normalize(t1);
  cross3(n0, t1, t2);
}

bool invert_membrane_shape_tensor(const double K[9], const double n0[3], double lambda_ref,
                                  double Kinv[9], double *lambda_max)
{
  for (int k = 0; k < 9; k++) Kinv[k] = 0.0;
  if (lambda_max) *lambda_max = 0.0;
  double t[2][3];
  tangent_frame(n0, t[0], t[1]);
  double kt[2][3], k2[2][2];
  for (int a = 0; a < 2; a++) apply(K, t[a], kt[a]);
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) k2[a][b] = dot(t[a], kt[b]);
  const double k01 = 0.5 * (k2[0][1] + k2[1][0]);
  if (!std::isfinite(k2[0][0]) || !std::isfinite(k2[1][1]) || !std::isfinite(k01)) return false;
  const double mean = 0.5 * (k2[0][0] + k2[1][1]);
  const double rad = std::hypot(0.5 * (k2[0][0] - k2[1][1]), k01);
  const double lmax = mean + rad, lmin = mean - rad;
  if (lambda_max) *lambda_max = lmax;
  if (!(lmax > 0.0) || !(lmin >= kMinShapeConditioning * std::max(lmax, lambda_ref))) return false;
  const double det = k2[0][0] * k2[1][1] - k01 * k01;
  const double inv[2][2] = {{k2[1][1] / det, -k01 / det}, {-k01 / det, k2[0][0] / det}};
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) {
      double v = 0.0;
      for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) v += t[a][r] * inv[a][b] * t[b][c];
      Kinv[3 * r + c] = v;
    }
  // exactly symmetric
  for (int r = 0; r < 3; r++)
    for (int c = r + 1; c < 3; c++) Kinv[3 * c + r] = Kinv[3 * r + c];
  return true;
}

double membrane_state(const Material &material, const double M[9], const double Kinv[9],
                      const double n0[3], double F[9], double A[9], double H[6])
{
  const RowMatrix3d kinv = Eigen::Map<const RowMatrix3d>(Kinv);
  const RowMatrix3d a = Eigen::Map<const RowMatrix3d>(M) * kinv;
  double t1[3], t2[3];
  tangent_frame(n0, t1, t2);
  double a1[3], a2[3];
  apply(a.data(), t1, a1);
  apply(a.data(), t2, a2);

  // the current frame (e1, e2, n): n the unit normal of the image of the tangent plane, e1 along
  // the longer image of t1 and t2
  const double l1 = std::sqrt(dot(a1, a1)), l2 = std::sqrt(dot(a2, a2));
  const double lmax = std::max(l1, l2);
  double e1[3], e2[3], n[3];
  cross3(a1, a2, n);
  const double area = std::sqrt(dot(n, n));
  if (lmax > 0.0) {
    const double *longer = l1 >= l2 ? a1 : a2;
    for (int k = 0; k < 3; k++) e1[k] = longer[k] / lmax;
  } else {
    for (int k = 0; k < 3; k++) e1[k] = t1[k];
  }
  if (area > 1.0e-14 * lmax * lmax) {
    for (int k = 0; k < 3; k++) n[k] /= area;
  } else {
    // collapsed to a line or a point: the normal nearest to n0 (or to t2) perpendicular to e1
    const double *near = std::fabs(dot(n0, e1)) < 0.9 ? n0 : t2;
    const double along = dot(near, e1);
    for (int k = 0; k < 3; k++) n[k] = near[k] - along * e1[k];
    normalize(n);
  }
  cross3(n, e1, e2);
  double m00 = dot(e1, a1), m01 = dot(e1, a2), m10 = dot(e2, a1), m11 = dot(e2, a2);
  if (m00 * m11 - m01 * m10 < 0.0) {
    // only in the collapsed case: orient n so that the in-plane map keeps its orientation
    for (int k = 0; k < 3; k++) {
      n[k] = -n[k];
      e2[k] = -e2[k];
    }
    m10 = -m10;
    m11 = -m11;
  }

  // F = U diag(s1, s2, s3) V^T with U = [E u1, E u2, n], V = [T v1, T v2, n0]
  const SVD2 d = svd2(m00, m01, m10, m11);
  SignedSVD svd;
  const double u1[2] = {d.cphi, d.sphi}, u2[2] = {-d.sphi, d.cphi};
  const double v1[2] = {d.ctheta, -d.stheta}, v2[2] = {d.stheta, d.ctheta};
  for (int k = 0; k < 3; k++) {
    svd.U(k, 0) = u1[0] * e1[k] + u1[1] * e2[k];
    svd.U(k, 1) = u2[0] * e1[k] + u2[1] * e2[k];
    svd.U(k, 2) = n[k];
    svd.V(k, 0) = v1[0] * t1[k] + v1[1] * t2[k];
    svd.V(k, 1) = v2[0] * t1[k] + v2[1] * t2[k];
    svd.V(k, 2) = n0[k];
  }
  const double s1 = d.s1, s2 = std::max(d.s2, 0.0);
  svd.s = Eigen::Vector3d(s1, s2, material.plane_stress_stretch(s1, s2));

  ParticleStress ps;
  stress_from_svd(material, svd, ps, H != nullptr);
  const RowMatrix3d f = svd.U * svd.s.asDiagonal() * svd.V.transpose();
  Eigen::Map<RowMatrix3d> fout(F), aout(A);
  fout = f;
  aout = ps.P * kinv;
  if (H) {
    Eigen::Vector3d c = ps.c;
    c(2) = 0.0;
    ParticleStress in_plane = ps;
    in_plane.c = c;
    implicit_stiffness(in_plane, 0.5 * (Kinv[0] + Kinv[4] + Kinv[8]), H);
  }
  return ps.W;
}

double membrane_stabilization_modulus(double Cs, double K, const double Kinv[9])
{
  return 2.4 * Cs * K * (Kinv[0] + Kinv[4] + Kinv[8]);
}

}    // namespace PeriSISSM
