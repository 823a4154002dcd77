// Chebyshev acceleration of the SISSM sweeps (solvers/chebyshev.h, solvers/jacobi.h): the weights,
// and on a linear SPD system whose sweep has a known spectral radius, fewer sweeps to a tolerance
// and a closer iterate after a fixed number of sweeps, at the same fixed point.

#include "linalg/reductions.h"
#include "solvers/chebyshev.h"
#include "solvers/jacobi.h"
#include "solvers/system.h"

#include "springs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace PeriSISSM;
using PeriSISSMTest::Table;

// A chain of n unit particles joined by linear springs k, the ends tied to fixed points, each with
// a mass term m, under loads b: r = b - A y, A = m I + k tridiag(-1, 2, -1) per component (SPD).
// The SISSM block of every row is (m + 2k) I, so the sweep's iteration matrix I - D^-1 A has the
// eigenvalues 2k cos(j pi / (n + 1)) / (m + 2k), j = 1..n: its spectral radius is rho() below.
class LinearChain : public NonlinearSystem {
 public:
  LinearChain(int n, double m, double k) :
      n_(n), m_(m), k_(k), y(n), y0(n), res(n), b(n), red_(n), mask_(n, 1), ones_(n, 1.0)
  {
    rows_.n = n;
    rows_.mask = mask_.data();
    rows_.bit = 1;
    rows_.volume = ones_.data();
    rows_.density = ones_.data();
    for (int i = 0; i < n; i++)
      for (int c = 0; c < 3; c++) b.rows[i][c] = std::sin(1.0 + 0.7 * i + 2.1 * c);
  }
  double rho() const { return 2.0 * k_ * std::cos(M_PI / (n_ + 1)) / (m_ + 2.0 * k_); }
  // the exact solution A^-1 b, component c of row i (Thomas algorithm)
  std::vector<double> solution(int c) const
  {
    std::vector<double> cp(n_), dp(n_), x(n_);
    const double diag = m_ + 2.0 * k_, off = -k_;
    for (int i = 0; i < n_; i++) {
      const double den = diag - (i > 0 ? off * cp[i - 1] : 0.0);
      cp[i] = off / den;
      dp[i] = (b.rows[i][c] - (i > 0 ? off * dp[i - 1] : 0.0)) / den;
    }
    for (int i = n_ - 1; i >= 0; i--) x[i] = dp[i] - (i + 1 < n_ ? cp[i] * x[i + 1] : 0.0);
    return x;
  }
  // max_i,c |y - A^-1 b|
  double error() const
  {
    double e = 0.0;
    for (int c = 0; c < 3; c++) {
      const std::vector<double> x = solution(c);
      for (int i = 0; i < n_; i++) e = std::max(e, std::fabs(y.rows[i][c] - x[i]));
    }
    return e;
  }

  const Rows &rows() const override { return rows_; }
  Reductions &reductions() override { return red_; }
  double **unknowns() override { return y.ptr(); }
  void evaluate(bool) override
  {
    evals_++;
    for (int i = 0; i < n_; i++)
      for (int c = 0; c < 3; c++) {
        const double left = i > 0 ? y.rows[i - 1][c] : 0.0;
        const double right = i + 1 < n_ ? y.rows[i + 1][c] : 0.0;
        res.rows[i][c] =
            b.rows[i][c] - m_ * y.rows[i][c] - k_ * (2.0 * y.rows[i][c] - left - right);
      }
  }
  double **residual() override { return res.ptr(); }
  int evaluations() const override { return evals_; }
  bool evaluation_complete() const override { return true; }
  bool stalled() const override { return false; }
  void block(int, double D[6]) const override
  {
    D[0] = D[1] = D[2] = m_ + 2.0 * k_;
    D[3] = D[4] = D[5] = 0.0;
  }
  double step_tolerance() override { return tol; }
  double **start() override { return y0.ptr(); }
  void check_finite() override {}

 private:
  int n_;
  double m_, k_;

 public:
  double tol = 1e-10;
  Table y, y0, res, b;

 private:
  int evals_ = 0;
  SerialReductions red_;
  std::vector<int> mask_;
  std::vector<double> ones_;
  Rows rows_;
};

// the limit of the weights, 2 / (1 + sqrt(1 - rho^2))
double limit_of_weights(double rho)
{
  return 2.0 / (1.0 + std::sqrt(1.0 - rho * rho));
}

TEST(Chebyshev, WeightsFollowTheRecurrence)
{
  const double rho = 0.9;
  ChebyshevWeights w(rho);
  EXPECT_EQ(w.next(), 1.0);
  double omega = w.next();
  EXPECT_DOUBLE_EQ(omega, 2.0 / (2.0 - rho * rho));
  for (int k = 0; k < 5; k++) {
    const double next = w.next();
    EXPECT_DOUBLE_EQ(next, 4.0 / (4.0 - rho * rho * omega));
    EXPECT_LT(next, omega);    // omega_2 is the largest
    omega = next;
  }
  for (int k = 0; k < 200; k++) omega = w.next();
  EXPECT_NEAR(omega, limit_of_weights(rho), 1e-12);
  EXPECT_GT(omega, 1.0);
  EXPECT_LT(limit_of_weights(0.999), 2.0);
  ChebyshevWeights off(0.0);
  for (int k = 0; k < 10; k++) EXPECT_EQ(off.next(), 1.0);
}

// (n = 20, m = 1, k = 50: rho = 0.979; to reduce the error by 1e-10 the plain sweep needs about
// ln(1e-10) / ln(rho) = 1087 sweeps, the Chebyshev bound (rho / (1 + sqrt(1 - rho^2)))^k about
// 111; measured to the residual 1e-10: 935 and 117 evaluations)
TEST(Chebyshev, ReachesTheToleranceInFewerSweepsAtTheSameFixedPoint)
{
  LinearChain plain(20, 1.0, 50.0), fast(20, 1.0, 50.0);
  Table yprev(20);
  SweepMemory memory;
  memory.yprev = yprev.ptr();
  const SolveResult rp = solve_jacobi(plain, 5000, SweepMemory());
  const SolveResult rf = solve_jacobi(fast, 5000, memory, fast.rho());
  ASSERT_TRUE(rp.converged()) << rp.measure;
  ASSERT_TRUE(rf.converged()) << rf.measure;
  EXPECT_GT(plain.evaluations(), 900);
  EXPECT_LT(fast.evaluations(), 150) << fast.evaluations();
  // |r| < 1e-10 bounds |y - y*| by |A^-1| 1e-10 = 1e-10 / m (and the last sweep moves closer)
  EXPECT_LT(plain.error(), 1e-10);
  EXPECT_LT(fast.error(), 1e-10);
}

// A fixed budget (the authors' mode): after 10 and after 30 sweeps the accelerated iterate is
// closer to the solution for rho at the true spectral radius (0.979) and for a small rho (0.5:
// weights at most 1.143). An overestimate (0.990) starts with weights that are too large: closer
// after 30 sweeps, but after 10 its largest error exceeds the plain sweeps' (measured 0.026
// against 0.019).
TEST(Chebyshev, FixedBudgetEndsCloser)
{
  for (int sweeps : {10, 30}) {
    LinearChain plain(20, 1.0, 50.0);
    solve_jacobi(plain, sweeps, SweepMemory());
    const double e_plain = plain.error();
    const double over = 0.5 * (1.0 + plain.rho());
    for (double rho : {plain.rho(), over, 0.5}) {
      LinearChain fast(20, 1.0, 50.0);
      Table yprev(20);
      SweepMemory memory;
      memory.yprev = yprev.ptr();
      solve_jacobi(fast, sweeps, memory, rho);
      EXPECT_EQ(fast.evaluations(), sweeps);
      if (rho == over && sweeps == 10)
        EXPECT_GT(fast.error(), e_plain);
      else
        EXPECT_LT(fast.error(), e_plain) << sweeps << " sweeps, rho " << rho;
    }
  }
}

// rho 0 is the plain sweep, bit for bit, with or without the row of earlier iterates.
TEST(Chebyshev, ZeroRhoIsThePlainSweep)
{
  LinearChain a(20, 1.0, 50.0), b(20, 1.0, 50.0);
  Table yprev(20);
  SweepMemory memory;
  memory.yprev = yprev.ptr();
  solve_jacobi(a, 25, SweepMemory());
  solve_jacobi(b, 25, memory, 0.0);
  EXPECT_EQ(a.y.data, b.y.data);
}

// On the nonlinear hanging chain of the solver tests (stiff springs, backward Euler), relax yes
// with chebyshev reaches the step that plain relaxed sweeps reach, in fewer sweeps.
TEST(Chebyshev, RelaxedSweepsOfANonlinearStep)
{
  const int n = 12;
  const double h = 0.05;
  PeriSISSMTest::Springs a = PeriSISSMTest::chain(n, h), b = PeriSISSMTest::chain(n, h);
  a.begin();
  b.begin();
  Table ra(n), da(n), rb(n), db(n), yprev(n);
  const SolveResult sa = solve_jacobi(a, 20000, {ra.ptr(), da.ptr(), nullptr});
  const SolveResult sb = solve_jacobi(b, 20000, {rb.ptr(), db.ptr(), yprev.ptr()}, 0.99);
  ASSERT_TRUE(sa.converged()) << sa.measure;
  ASSERT_TRUE(sb.converged()) << sb.measure;
  EXPECT_LT(b.evaluations(), a.evaluations() / 2) << b.evaluations() << " vs " << a.evaluations();
  double diff = 0.0;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) diff = std::max(diff, std::fabs(a.y.rows[i][k] - b.y.rows[i][k]));
  EXPECT_LT(diff, 1e-8);
}

}    // namespace
