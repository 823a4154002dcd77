// Fast signed SVD of a 3x3 matrix (see fast_svd.h).

#include "linalg/fast_svd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#ifdef PERISISSM_CPU_DISPATCH
#include "linalg/double4.h"
#endif

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
        fmax = std::max(fmax, std::fabs(a));
      }
    exponent = 0;
    // (the convergence test squares Gram entries: fourth powers of F's entries, which must
    // neither overflow nor underflow)
    if (fmax != 0.0 && (fmax > 0x1p200 || fmax < 0x1p-200)) {
      std::frexp(fmax, &exponent);
      for (auto &col : m.b)
        for (double &a : col) a = std::ldexp(a, -exponent);
    }
    return true;
  }

  // The end of steps 3 and 4: U, V (V[k][r]: row r of column k), s = the diagonal of R into out, the
  // order repaired, the scaling undone
  void unload(const double U[3][3], const double V[3][3], const double s[3], int exponent,
              SignedSVD &out)
  {
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) {
        out.U(r, c) = U[r][c];
        out.V(r, c) = V[c][r];
      }
    // (+ 0.0 turns a -0 into +0: "s_3 < 0" means inverted, not singular)
    out.s = Eigen::Vector3d(s[0] + 0.0, s[1] + 0.0, s[2] + 0.0);
    order(out);
    if (exponent != 0)
      for (int k = 0; k < 3; k++) out.s(k) = std::ldexp(out.s(k), exponent);
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
    const double s[3] = {R[0][0], R[1][1], R[2][2]};
    unload(U, m.v, s, exponent, out);
  }

#ifdef PERISISSM_CPU_DISPATCH
  // Four matrices at once, one per lane of 4-wide AVX registers (compiled for x86-64-v3): every
  // lane does the scalar operations of orthogonalize(Columns &), sort_columns() and the three
  // givens() of finish() on its matrix in the same order, each correctly rounded (add, subtract,
  // multiply, divide, square root; no fused multiply-add: this file is compiled with
  // -ffp-contract=off), so each matrix ends with the same bits as it would alone. A rotation,
  // swap or Givens rotation a lane skips (its pair counts as orthogonal, its matrix is done, its
  // columns are in order, its r is 0) leaves its lane untouched by a blend, not by a rotation
  // through angle 0. The skipped lanes' arithmetic is still done and may divide by zero: that
  // sets the floating-point exception flags (results unaffected; nothing here runs with
  // exceptions trapped).
  struct Columns4 {
    Double4 b[3][3];    // b[k][r]: row r of column k of B, lane l of matrix l
    Double4 v[3][3];
  };

  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 dot3x4(const Double4 *x,
                                                                      const Double4 *y)
  {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x[0], y[0]), _mm256_mul_pd(x[1], y[1])),
                         _mm256_mul_pd(x[2], y[2]));
  }

  // rotate(x, y, c, s) in the lanes of mask
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void
  rotate4(Double4 *x, Double4 *y, Double4 c, Double4 s, Double4 mask)
  {
    for (int k = 0; k < 3; k++) {
      const Double4 a = x[k], b = y[k];
      const Double4 xn = _mm256_sub_pd(_mm256_mul_pd(c, a), _mm256_mul_pd(s, b));
      const Double4 yn = _mm256_add_pd(_mm256_mul_pd(s, a), _mm256_mul_pd(c, b));
      x[k] = _mm256_blendv_pd(a, xn, mask);
      y[k] = _mm256_blendv_pd(b, yn, mask);
    }
  }

  // jacobi_rotation(m, r) in the lanes of active; returns the lanes that rotated
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline Double4 jacobi_rotation4(Columns4 &m, int r,
                                                                                Double4 active)
  {
    static constexpr int P[3] = {0, 0, 1}, Q[3] = {1, 2, 2};
    const Double4 tol2 = splat(kOrthogonal * kOrthogonal);
    const Double4 sign = splat(-0.0);
    Double4 *bp = m.b[P[r]], *bq = m.b[Q[r]];
    const Double4 alpha = dot3x4(bp, bp), beta = dot3x4(bq, bq), gamma = dot3x4(bp, bq);
    const Double4 tol = _mm256_mul_pd(_mm256_mul_pd(tol2, alpha), beta);
    const Double4 go = _mm256_and_pd(active, greater4(_mm256_mul_pd(gamma, gamma), tol));
    if (!any4(go)) return go;
    const Double4 d = _mm256_mul_pd(splat(0.5), _mm256_sub_pd(beta, alpha));
    const Double4 absd = _mm256_andnot_pd(sign, d);
    const Double4 g2 = _mm256_mul_pd(gamma, gamma);
    const Double4 a = _mm256_add_pd(absd, _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(d, d), g2)));
    const Double4 inv =
        _mm256_div_pd(splat(1.0), _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(a, a), g2)));
    Double4 c = _mm256_mul_pd(a, inv);
    Double4 s =
        _mm256_mul_pd(_mm256_mul_pd(_mm256_or_pd(_mm256_and_pd(sign, d), splat(1.0)), gamma), inv);
    const Double4 small = _mm256_and_pd(
        go, less4(_mm256_andnot_pd(sign, gamma), _mm256_mul_pd(splat(kSmallAngle), absd)));
    if (any4(small)) {
      const Double4 t = _mm256_div_pd(gamma, _mm256_mul_pd(splat(2.0), d));
      const Double4 ct = _mm256_sub_pd(splat(1.0), _mm256_mul_pd(_mm256_mul_pd(splat(0.5), t), t));
      c = _mm256_blendv_pd(c, ct, small);
      s = _mm256_blendv_pd(s, t, small);
    }
    rotate4(bp, bq, c, s, go);
    rotate4(m.v[P[r]], m.v[Q[r]], c, s, go);
    return go;
  }

  // orthogonalize(Columns &) of each lane not set in done (lanes set there are left alone)
  PERISISSM_FUSED_TARGET void orthogonalize4(Columns4 &m, Double4 done)
  {
    const Double4 all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for (int sweep = 0; sweep < kMaxSweeps && _mm256_movemask_pd(done) != 0xF; sweep++) {
      const Double4 active = _mm256_andnot_pd(done, all);
      Double4 rotated = _mm256_setzero_pd();
      for (int r = 0; r < 3; r++) rotated = or4(rotated, jacobi_rotation4(m, r, active));
      done = or4(done, _mm256_andnot_pd(rotated, all));
    }
  }

  // swap(p, q) of sort_columns() in the lanes where n[p] < n[q]
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void swap_columns4(Columns4 &m, Double4 n[3],
                                                                          int p, int q)
  {
    const Double4 sign = splat(-0.0);
    const Double4 mask = less4(n[p], n[q]);
    const Double4 np = n[p];
    n[p] = _mm256_blendv_pd(np, n[q], mask);
    n[q] = _mm256_blendv_pd(n[q], np, mask);
    for (int k = 0; k < 3; k++) {
      const Double4 bp = m.b[p][k], bq = m.b[q][k], vp = m.v[p][k], vq = m.v[q][k];
      m.b[p][k] = _mm256_blendv_pd(bp, bq, mask);
      m.b[q][k] = _mm256_blendv_pd(bq, _mm256_xor_pd(bp, sign), mask);
      m.v[p][k] = _mm256_blendv_pd(vp, vq, mask);
      m.v[q][k] = _mm256_blendv_pd(vq, _mm256_xor_pd(vp, sign), mask);
    }
  }

  // sort_columns(m) in every lane
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void sort_columns4(Columns4 &m)
  {
    Double4 n[3] = {dot3x4(m.b[0], m.b[0]), dot3x4(m.b[1], m.b[1]), dot3x4(m.b[2], m.b[2])};
    swap_columns4(m, n, 0, 1);
    swap_columns4(m, n, 0, 2);
    swap_columns4(m, n, 1, 2);
  }

  // a <- c a + s b, b <- -s a + c b in the lanes of mask (a row or column pair of givens())
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void
  turn4(Double4 &a, Double4 &b, Double4 c, Double4 s, Double4 minus_s, Double4 mask)
  {
    const Double4 an = _mm256_add_pd(_mm256_mul_pd(c, a), _mm256_mul_pd(s, b));
    const Double4 bn = _mm256_add_pd(_mm256_mul_pd(minus_s, a), _mm256_mul_pd(c, b));
    a = _mm256_blendv_pd(a, an, mask);
    b = _mm256_blendv_pd(b, bn, mask);
  }

  // givens(R, U, p, q, col) in every lane
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void
  givens4(Double4 R[3][3], Double4 U[3][3], int p, int q, int col)
  {
    const Double4 x = R[p][col], y = R[q][col];
    const Double4 r = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)));
    const Double4 go = _mm256_cmp_pd(r, _mm256_setzero_pd(), _CMP_NEQ_UQ);
    if (!any4(go)) return;
    const Double4 c = _mm256_div_pd(x, r), s = _mm256_div_pd(y, r);
    const Double4 minus_s = _mm256_xor_pd(s, splat(-0.0));
    for (int k = 0; k < 3; k++) turn4(R[p][k], R[q][k], c, s, minus_s, go);
    R[q][col] = _mm256_blendv_pd(R[q][col], _mm256_setzero_pd(), go);
    for (int k = 0; k < 3; k++) turn4(U[k][p], U[k][q], c, s, minus_s, go);
  }

  // Steps 2 and 3 of the method for four matrices (lanes with ok[l] false are left alone): m[l]
  // in, U[l], V[l] (by columns as Columns::v) and the diagonal s[l] of R out
  PERISISSM_FUSED_TARGET void svd4(const Columns m[4], const bool ok[4], double U[4][3][3],
                                   double V[4][3][3], double s[4][3])
  {
    Columns4 m4;
    for (int k = 0; k < 3; k++)
      for (int r = 0; r < 3; r++) {
        m4.b[k][r] = _mm256_setr_pd(m[0].b[k][r], m[1].b[k][r], m[2].b[k][r], m[3].b[k][r]);
        m4.v[k][r] = _mm256_setr_pd(m[0].v[k][r], m[1].v[k][r], m[2].v[k][r], m[3].v[k][r]);
      }
    const Double4 done = _mm256_castsi256_pd(
        _mm256_setr_epi64x(ok[0] ? 0 : -1, ok[1] ? 0 : -1, ok[2] ? 0 : -1, ok[3] ? 0 : -1));
    orthogonalize4(m4, done);
    sort_columns4(m4);
    Double4 R[3][3], Q[3][3];
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) {
        R[r][c] = m4.b[c][r];
        Q[r][c] = splat(r == c ? 1.0 : 0.0);
      }
    givens4(R, Q, 0, 1, 0);
    givens4(R, Q, 0, 2, 0);
    givens4(R, Q, 1, 2, 1);
    double lanes[4];
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) {
        store4(lanes, Q[r][c]);
        for (int l = 0; l < 4; l++) U[l][r][c] = lanes[l];
        store4(lanes, m4.v[r][c]);
        for (int l = 0; l < 4; l++) V[l][r][c] = lanes[l];
      }
    for (int k = 0; k < 3; k++) {
      store4(lanes, R[k][k]);
      for (int l = 0; l < 4; l++) s[l][k] = lanes[l];
    }
  }
#endif

}    // namespace

// Method:
// 1. Scale F by a power of two (exact) when its largest entry is outside [2^-200, 2^200], so
//    that the squared Gram entries of the convergence test (fourth powers of F's entries)
//    neither overflow nor underflow.
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
  if (fa && fb)
    orthogonalize(ma, mb);
  else if (fa)
    orthogonalize(ma);
  else if (fb)
    orthogonalize(mb);
  if (fa) finish(ma, ea, a);
  if (fb) finish(mb, eb, b);
}

void fast_signed_svd(const Eigen::Matrix3d F[4], SignedSVD out[4])
{
#ifdef PERISISSM_CPU_DISPATCH
  if (x86_64_v3()) {
    Columns m[4];
    int e[4];
    bool ok[4];
    for (int l = 0; l < 4; l++) {
      ok[l] = load(F[l], m[l], e[l], out[l]);
      if (!ok[l]) m[l] = Columns{};    // (load stops at a non-finite entry: zeros instead)
    }
    double U[4][3][3], V[4][3][3], s[4][3];
    svd4(m, ok, U, V, s);
    for (int l = 0; l < 4; l++)
      if (ok[l]) unload(U[l], V[l], s[l], e[l], out[l]);
    return;
  }
#endif
  fast_signed_svd(F[0], F[1], out[0], out[1]);
  fast_signed_svd(F[2], F[3], out[2], out[3]);
}

}    // namespace PeriSISSM
