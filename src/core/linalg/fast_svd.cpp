// Fast signed SVD of a 3x3 matrix (see fast_svd.h).

#include "linalg/fast_svd.h"

#include <cmath>
#include <limits>
#include <utility>

namespace PeriSISSM {

namespace {

// Columns of B and V as 3-vectors: b[k] is column k.
struct Columns {
  double b[3][3];
  double v[3][3];
};

double dot3(const double *x, const double *y)
{
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

// x <- c x - s y, y <- s x + c y (columns p and q of B V = F V times the plane rotation
// J = [c s; -s c], which keeps B = F V)
void rotate(double *x, double *y, double c, double s)
{
  for (int k = 0; k < 3; k++) {
    const double a = x[k], b = y[k];
    x[k] = c * a - s * b;
    y[k] = s * a + c * b;
  }
}

// Convergence test of the one-sided Jacobi method: columns p, q count as orthogonal when
// |b_p . b_q| <= kOrthogonal |b_p| |b_q| (a few units of round-off; then rotating changes
// F = B V^T by less than round-off).
constexpr double kOrthogonal = 4.0 * std::numeric_limits<double>::epsilon();
constexpr int kMaxSweeps = 30;
constexpr double kSmallAngle = 2.0e-8;

// One-sided (Hestenes) Jacobi: rotate pairs of columns of B = F V until all are orthogonal.
// Each rotation diagonalizes the 2x2 Gram matrix [alpha gamma; gamma beta] of its pair with the
// smaller angle: with d = (beta - alpha) / 2, tan(theta) = t = sign(d) gamma / (|d| +
// sqrt(d^2 + gamma^2)) (Golub and Van Loan, Matrix Computations, 8.5.2, multiplied through by
// |gamma|), so that c = cos(theta) = (|d| + r) / h and s = sin(theta) = sign(d) gamma / h with
// r = sqrt(d^2 + gamma^2), h = sqrt((|d| + r)^2 + gamma^2): two square roots and one division
// on the critical path. The Gram entries come from the current columns, not from F^T F formed
// once, so small singular values keep their relative accuracy (Demmel and Veselic 1992);
// convergence is quadratic.
// One rotation of the pair r (0: columns 0-1, 1: 0-2, 2: 1-2); false when the pair already
// counts as orthogonal (nothing done)
inline bool jacobi_rotation(Columns &m, int r)
{
  static constexpr int P[3] = {0, 0, 1}, Q[3] = {1, 2, 2};
  constexpr double tol2 = kOrthogonal * kOrthogonal;
  double *bp = m.b[P[r]], *bq = m.b[Q[r]];
  const double alpha = dot3(bp, bp), beta = dot3(bq, bq), gamma = dot3(bp, bq);
  if (!(gamma * gamma > tol2 * alpha * beta)) return false;
  const double d = 0.5 * (beta - alpha);
  double c, s;
  if (std::fabs(gamma) < kSmallAngle * std::fabs(d)) {
    // |t| < 1e-8: t = gamma / (2 d) to a relative t^2 < 1e-16, c = 1 - t^2/2 and s = t
    // to round-off (c^2 + s^2 = 1 + t^4/4)
    s = gamma / (2.0 * d);
    c = 1.0 - 0.5 * s * s;
  } else {
    const double a = std::fabs(d) + std::sqrt(d * d + gamma * gamma);
    const double inv = 1.0 / std::sqrt(a * a + gamma * gamma);
    c = a * inv;
    s = std::copysign(1.0, d) * gamma * inv;
  }
  rotate(bp, bq, c, s);
  rotate(m.v[P[r]], m.v[Q[r]], c, s);
  return true;
}

// Cyclic sweeps until a sweep rotates nothing.
void orthogonalize(Columns &m)
{
  for (int sweep = 0; sweep < kMaxSweeps; sweep++) {
    bool rotated = false;
    for (int r = 0; r < 3; r++) rotated |= jacobi_rotation(m, r);
    if (!rotated) break;
  }
}

// The same for two matrices at once, each exactly as orthogonalize() would (a matrix whose sweep
// rotated nothing is left alone): the two chains of dependent square roots and divisions are
// independent, and the processor overlaps them.
void orthogonalize(Columns &a, Columns &b)
{
  bool done_a = false, done_b = false;
  for (int sweep = 0; sweep < kMaxSweeps && !(done_a && done_b); sweep++) {
    bool rotated_a = false, rotated_b = false;
    for (int r = 0; r < 3; r++) {
      if (!done_a) rotated_a |= jacobi_rotation(a, r);
      if (!done_b) rotated_b |= jacobi_rotation(b, r);
    }
    done_a = done_a || !rotated_a;
    done_b = done_b || !rotated_b;
  }
}

// Columns in decreasing norm. A swap negates one of the two columns (of B and V alike, so
// B = F V still holds) to keep det V = +1.
void sort_columns(Columns &m)
{
  double n[3] = {dot3(m.b[0], m.b[0]), dot3(m.b[1], m.b[1]), dot3(m.b[2], m.b[2])};
  auto swap = [&](int p, int q) {
    std::swap(n[p], n[q]);
    for (int k = 0; k < 3; k++) {
      std::swap(m.b[p][k], m.b[q][k]);
      std::swap(m.v[p][k], m.v[q][k]);
      m.b[q][k] = -m.b[q][k];
      m.v[q][k] = -m.v[q][k];
    }
  };
  if (n[0] < n[1]) swap(0, 1);
  if (n[0] < n[2]) swap(0, 2);
  if (n[1] < n[2]) swap(1, 2);
}

// Givens rotation of rows p, q of R (3x3, row-major, R[r][col]) that zeroes R[q][col] and
// leaves R[p][col] = hypot >= 0; U <- U G^T keeps U R unchanged.
void givens(double R[3][3], double U[3][3], int p, int q, int col)
{
  const double x = R[p][col], y = R[q][col];
  const double r = std::sqrt(x * x + y * y);
  if (r == 0.0) return;
  const double c = x / r, s = y / r;
  for (int k = 0; k < 3; k++) {
    const double a = R[p][k], b = R[q][k];
    R[p][k] = c * a + s * b;
    R[q][k] = -s * a + c * b;
  }
  R[q][col] = 0.0;
  for (int k = 0; k < 3; k++) {
    const double a = U[k][p], b = U[k][q];
    U[k][p] = c * a + s * b;
    U[k][q] = -s * a + c * b;
  }
}

// Swap singular triplets p and q, keeping det U = det V = +1: swapping columns of both U and V
// reverses both determinants; negating the remaining column o of both restores them
// (u_o s_o v_o^T is unchanged).
void swap_triplets(SignedSVD &d, int p, int q)
{
  const int o = 3 - p - q;
  d.U.col(p).swap(d.U.col(q));
  d.V.col(p).swap(d.V.col(q));
  std::swap(d.s(p), d.s(q));
  d.U.col(o) = -d.U.col(o);
  d.V.col(o) = -d.V.col(o);
}

// Restore |s_1| >= |s_2| >= |s_3| with s_1, s_2 >= 0 where round-off in nearly repeated values
// broke it. Negating s_k and s_3 together with columns k and 3 of U keeps U diag(s) V^T and
// det U.
void order(SignedSVD &d)
{
  for (int pass = 0; pass < 2; pass++) {
    if (std::fabs(d.s(0)) < std::fabs(d.s(1))) swap_triplets(d, 0, 1);
    if (std::fabs(d.s(1)) < std::fabs(d.s(2))) swap_triplets(d, 1, 2);
  }
  for (int k = 0; k < 2; k++)
    if (d.s(k) < 0.0) {
      d.s(k) = -d.s(k);
      d.s(2) = -d.s(2);
      d.U.col(k) = -d.U.col(k);
      d.U.col(2) = -d.U.col(2);
    }
}

// Step 1 of the method (columns of F into m, V = I, scaled); false for a non-finite F (out
// then set)
bool load(const Eigen::Matrix3d &F, Columns &m, int &exponent, SignedSVD &out)
{
  double fmax = 0.0;
  for (int c = 0; c < 3; c++)
    for (int r = 0; r < 3; r++) {
      const double a = F(r, c);
      if (!std::isfinite(a)) {
        out.U.setIdentity();
        out.V.setIdentity();
        out.s.setConstant(std::numeric_limits<double>::quiet_NaN());
        return false;
      }
      m.b[c][r] = a;
      m.v[c][r] = (r == c) ? 1.0 : 0.0;
      fmax = std::fmax(fmax, std::fabs(a));
    }
  exponent = 0;
  if (fmax != 0.0 && (fmax > 0x1p400 || fmax < 0x1p-400)) {
    std::frexp(fmax, &exponent);
    for (auto &col : m.b)
      for (double &a : col) a = std::ldexp(a, -exponent);
  }
  return true;
}

// Steps 3 and 4 of the method (fast_signed_svd() below)
void finish(Columns &m, int exponent, SignedSVD &out)
{
  sort_columns(m);
  double R[3][3], U[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) R[r][c] = m.b[c][r];
  givens(R, U, 0, 1, 0);
  givens(R, U, 0, 2, 0);
  givens(R, U, 1, 2, 1);

  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) {
      out.U(r, c) = U[r][c];
      out.V(r, c) = m.v[c][r];
    }
  // (+ 0.0 turns a -0 into +0: "s_3 < 0" means inverted, not singular)
  out.s = Eigen::Vector3d(R[0][0] + 0.0, R[1][1] + 0.0, R[2][2] + 0.0);
  order(out);
  if (exponent != 0)
    for (int k = 0; k < 3; k++) out.s(k) = std::ldexp(out.s(k), exponent);
}

}  // namespace

// Method:
// 1. Scale F by a power of two (exact) when its largest entry is outside [2^-400, 2^400], so
//    that the squared norms below neither overflow nor underflow.
// 2. One-sided Jacobi on B = F, V = I: B = F V with orthogonal columns, V a product of
//    rotations (det +1).
// 3. Sort the columns by norm; QR of B by three Givens rotations: B = U R, U a rotation; the
//    columns of B being orthogonal, R is diagonal up to round-off, and its diagonal is s:
//    R_11, R_22 >= 0 by construction, and sign(R_33) = sign(det B) = sign(det F) (det U =
//    det V = +1), the signed convention of signed_svd().
// 4. Repair the order where round-off swapped nearly repeated values; undo the scaling.
SignedSVD fast_signed_svd(const Eigen::Matrix3d &F)
{
  SignedSVD out;
  Columns m;
  int exponent;
  if (!load(F, m, exponent, out)) return out;
  orthogonalize(m);
  finish(m, exponent, out);
  return out;
}

void fast_signed_svd(const Eigen::Matrix3d &Fa, const Eigen::Matrix3d &Fb, SignedSVD &a,
                     SignedSVD &b)
{
  Columns ma, mb;
  int ea, eb;
  const bool fa = load(Fa, ma, ea, a), fb = load(Fb, mb, eb, b);
  if (fa && fb) orthogonalize(ma, mb);
  else if (fa) orthogonalize(ma);
  else if (fb) orthogonalize(mb);
  if (fa) finish(ma, ea, a);
  if (fb) finish(mb, eb, b);
}

}  // namespace PeriSISSM
