// The solvers alone, on toy systems without LAMMPS: backward-Euler steps of particles joined by
// nonlinear springs (a chain and a small lattice), solved by the SISSM Jacobi sweeps and by
// Newton-Krylov with the block preconditioner; and the momentum balance of a truncated solve.

#include "solvers/springs.h"

#include "linalg/reductions.h"
#include "solvers/jacobi.h"
#include "solvers/momentum.h"
#include "solvers/newton_krylov.h"
#include "solvers/preconditioner.h"
#include "solvers/system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using namespace PeriSISSM;
using namespace PeriSISSMTest;

// The chain's step solved by the sweeps (a, ra) and by Newton-Krylov with the blocks (b, rb);
// stall: Springs::stall_from of both
struct BothSolvers {
  Springs a, b;
  SolveResult ra, rb;
  BothSolvers(int n, double h, int stall = 0) : a(chain(n, h)), b(chain(n, h))
  {
    a.stall_from = b.stall_from = stall;
    a.begin();
    b.begin();
    ra = solve_jacobi(a, 20000, SweepMemory());
    BlockPreconditioner pc;
    KrylovTables kt(n);
    rb = solve_newton_krylov(b, pc, 200, kt.work());
  }
};

// Both solvers reach the backward-Euler step of the chain: the residual measure below the
// tolerance, the two solutions within the distance the tolerance allows (measure < tol bounds
// |y - y*| by about tol * size / (1 - contraction); 1e-8 here with tol 1e-10), Newton-Krylov
// in far fewer evaluations.
TEST(Solvers, JacobiAndNewtonKrylovReachTheSameStep)
{
  const int n = 12;
  BothSolvers s(n, 0.05);
  const Springs &a = s.a, &b = s.b;
  const SolveResult &ra = s.ra, &rb = s.rb;
  EXPECT_TRUE(ra.converged()) << ra.measure;
  EXPECT_TRUE(rb.converged()) << rb.measure;
  EXPECT_LT(b.evaluations(), a.evaluations() / 5) << b.evaluations() << " vs " << a.evaluations();
  double diff = 0.0, sag = 0.0;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      diff = std::max(diff, std::fabs(a.y.rows[i][k] - b.y.rows[i][k]));
      sag = std::max(sag, std::fabs(a.y.rows[i][k] - a.yn.rows[i][k]));
    }
  EXPECT_GT(sag, 1e-3);    // the step moved the chain
  EXPECT_LT(diff, 1e-8);
}

// A system whose moves stall (NonlinearSystem::stalled(): the contact candidates' reach used
// up) ends both solvers at that evaluation, unconverged, instead of at their budgets, with
// Newton-Krylov's unknowns at the last iterate it evaluated.
TEST(Solvers, AStalledIterateEndsTheSolve)
{
  const int n = 12;
  const double h = 0.05;
  for (int stall : {1, 2, 5}) {
    const BothSolvers s(n, h, stall);
    EXPECT_FALSE(s.ra.converged());
    EXPECT_FALSE(s.rb.converged());
    // (an iterate or a CG product's probe: both end Newton-Krylov)
    EXPECT_EQ(s.a.evaluations(), stall);
    EXPECT_EQ(s.b.evaluations(), stall);
    EXPECT_GT(s.rb.measure, s.rb.tolerance);
  }
  // Newton-Krylov's first iterate: no CG product at all
  Springs c = chain(n, h);
  c.stall_from = 1;
  c.begin();
  BlockPreconditioner pc;
  KrylovTables kt(n);
  const SolveResult rc = solve_newton_krylov(c, pc, 200, kt.work());
  EXPECT_EQ(c.evaluations(), 1);
  EXPECT_EQ(rc.newton, 0);
  // a stall at the first probe of a Newton step: the unknowns back at its base
  Springs d = chain(n, h);
  d.stall_from = 2;
  d.begin();
  std::vector<double> base;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) base.push_back(d.y.rows[i][k]);
  const SolveResult rd = solve_newton_krylov(d, pc, 200, kt.work());
  EXPECT_EQ(d.evaluations(), 2);
  EXPECT_EQ(rd.newton, 0);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) EXPECT_EQ(d.y.rows[i][k], base[3 * i + k]);
}

// The forcing term (NewtonForcing, newton_krylov.h): a solve hands the first Eisenstat-Walker
// term it computes (how far its linear model missed) to the next solve's first Newton step.
// Particles on linear anchors: the model misses only by the products' finite differences, so
// the term falls to its floor, 1e-4. A stretched chain of stiff nonlinear springs, shaken at a
// large step: its second Newton step's model misses by a tenth (measured 0.101); the same
// solve again takes that term for its first Newton step (measured: 347 CG iterations in all
// instead of 326; on this nearly linear chain a tight first step pays, on cloth in contact a
// loose one does, doc/fix_sissm.rst) and reaches the same step (within the tolerance's
// distance, as above).
TEST(Solvers, TheForcingTermIsHowFarTheLinearModelMissed)
{
  const int n = 6;
  const double h = 0.05;
  Springs lin(n, h);
  for (int i = 0; i < n; i++) {
    const double p[3] = {double(i), 0.3 * i, -0.2};
    lin.anchor(i, 50.0 / (h * h) * (1 + i), p);
  }
  lin.tol = 1e-13;
  lin.begin();
  BlockPreconditioner pc;
  KrylovTables kt(n);
  NewtonForcing forcing;
  KrylovWork w = kt.work();
  w.forcing = &forcing;
  ASSERT_TRUE(solve_newton_krylov(lin, pc, 200, w).converged());
  EXPECT_EQ(forcing.first, 1.0e-4);

  // a chain of stiff nonlinear springs stretched between its pinned ends, shaken (random
  // velocities) at a large step
  const int m = 40;
  auto shaken = [&]() {
    Springs c(m, 2 * h);
    for (int i = 0; i < m; i++) c.y.rows[i][0] = 1.2 * i;
    for (int i = 0; i + 1 < m; i++) c.spring(i, i + 1, 400.0 / (h * h), 1.0);
    c.pin(0);
    c.pin(m - 1);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> n01;
    for (int i = 1; i + 1 < m; i++)
      for (int k = 0; k < 3; k++) c.v.rows[i][k] = 0.3 * n01(rng);
    c.tol = 1e-10;
    c.begin();
    return c;
  };
  Springs a = shaken(), b = shaken();
  KrylovTables kc(m);
  NewtonForcing carried;
  KrylovWork wa = kc.work();
  wa.forcing = &carried;
  const SolveResult ra = solve_newton_krylov(a, pc, 1000, wa);
  ASSERT_TRUE(ra.converged());
  EXPECT_GT(carried.first, 0.03);
  EXPECT_LE(carried.first, kMaxForcing);
  std::printf("the chain's first forcing term %.3g; Newton steps %d, CG iterations %d\n",
              carried.first, ra.newton, ra.krylov);
  // again from the start, with the term carried
  KrylovWork wb = kc.work();
  wb.forcing = &carried;
  const SolveResult rb = solve_newton_krylov(b, pc, 1000, wb);
  ASSERT_TRUE(rb.converged());
  std::printf("started from it: Newton steps %d, CG iterations %d\n", rb.newton, rb.krylov);
  EXPECT_TRUE(rb.krylov != ra.krylov || rb.newton != ra.newton);
  double diff = 0.0;
  for (int i = 0; i < m; i++)
    for (int k = 0; k < 3; k++) diff = std::max(diff, std::fabs(a.y.rows[i][k] - b.y.rows[i][k]));
  EXPECT_LT(diff, 1e-7);
}

// Keyword error (newton_krylov.h) on one particle swinging on a stiff nonlinear spring from a
// pinned one: the block preconditioner is then the exact linearization (J is the particle's own
// block), i.e. an estimating preconditioner. The solve ends on the error rule with far fewer
// evaluations than a tight tolerance, and the iterate it accepts is within its own estimate
// (error times the step's motion, plus what the linearization misses: 10%) of the converged
// step. The block preconditioner itself does not claim to estimate: with it the rule is off.
struct EstimatingBlocks : BlockPreconditioner {
  bool estimates_error() const override { return true; }
};

TEST(Solvers, ErrorRuleStopsWithinItsEstimate)
{
  const double h = 0.05, error = 0.01;
  auto swing = [&]() {
    Springs s(2, h, make_time_scheme("genalpha", 0.8));
    s.y.rows[1][0] = 1.0;
    s.spring(0, 1, 400.0 / (h * h), 1.0);
    s.pin(0);
    s.g[2] = -10.0;
    s.v.rows[1][1] = 3.0;
    s.begin();
    return s;
  };
  Springs tight = swing(), loose = swing(), plain = swing();
  KrylovTables kt(2);
  EstimatingBlocks est;
  BlockPreconditioner block;
  tight.tol = 1e-13;
  const SolveResult rt = solve_newton_krylov(tight, block, 200, kt.work());
  ASSERT_TRUE(rt.converged());
  ASSERT_FALSE(rt.error_met);
  loose.tol = 1e-13;
  const SolveResult rl = solve_newton_krylov(loose, est, 200, kt.work(), error);
  EXPECT_TRUE(rl.error_met);
  EXPECT_TRUE(rl.converged());
  EXPECT_GT(rl.measure, rl.tolerance);    // the residual rule alone would go on
  EXPECT_LE(rl.error, error);
  EXPECT_LT(loose.evaluations(), tight.evaluations());
  double motion = 0.0, dist = 0.0;
  for (int k = 0; k < 3; k++) {
    motion += std::pow(tight.y.rows[1][k] - tight.yn.rows[1][k], 2);
    dist += std::pow(loose.y.rows[1][k] - tight.y.rows[1][k], 2);
  }
  EXPECT_GT(std::sqrt(motion), 0.05);    // the step moved the particle
  EXPECT_LT(std::sqrt(dist), 1.1 * error * std::sqrt(motion));
  plain.tol = 1e-13;
  const SolveResult rp = solve_newton_krylov(plain, block, 200, kt.work(), error);
  EXPECT_FALSE(rp.error_met);
  EXPECT_EQ(plain.evaluations(), tight.evaluations());
}

// A preconditioner whose answer is not a number (a broken set of user options) estimates no
// error: the rule never ends the step on it, the solve stays unconverged (measured before the
// guard: PETSc with an SOR smoother on the hanging cloth gave z = NaN, and every step ended on
// the rule after one evaluation while the cloth blew up).
struct NotANumber : BlockPreconditioner {
  bool estimates_error() const override { return true; }
  void apply(NonlinearSystem &sys, double **r, double **z) override
  {
    BlockPreconditioner::apply(sys, r, z);
    z[1][0] = std::nan("");
  }
};

TEST(Solvers, ErrorRuleIgnoresAnEstimateThatIsNotANumber)
{
  Springs s(2, 0.05, make_time_scheme("genalpha", 0.8));
  s.y.rows[1][0] = 1.0;
  s.spring(0, 1, 400.0 / (0.05 * 0.05), 1.0);
  s.pin(0);
  s.g[2] = -10.0;
  s.v.rows[1][1] = 3.0;
  s.begin();
  s.tol = 1e-13;
  KrylovTables kt(2);
  NotANumber nan;
  const SolveResult r = solve_newton_krylov(s, nan, 20, kt.work(), 0.01);
  EXPECT_FALSE(r.error_met);
  EXPECT_FALSE(r.converged());
}

// The documented equivalence: Newton-Krylov with a budget of one evaluation is the plain SISSM
// sweep, to the last bit.
TEST(Solvers, OneEvaluationOfKrylovIsOneSweep)
{
  Springs a = chain(8, 0.05), b = chain(8, 0.05);
  a.begin();
  b.begin();
  solve_jacobi(a, 1, SweepMemory());
  BlockPreconditioner pc;
  KrylovTables kt(8);
  solve_newton_krylov(b, pc, 1, kt.work());
  EXPECT_EQ(a.y.data, b.y.data);
  EXPECT_EQ(a.evaluations(), 1);
  EXPECT_EQ(b.evaluations(), 1);
}

// A small lattice (3 x 3 x 2, springs to the 18 nearest and face-diagonal neighbours, unequal
// densities and volumes, one face pinned) under a body force: Newton-Krylov converges within its
// budget and the converged step is a fixed point of the SISSM sweep (one more sweep moves no
// particle by more than the tolerance allows).
TEST(Solvers, LatticeStepIsAFixedPointOfTheSweep)
{
  const int nx = 3, ny = 3, nz = 2, n = nx * ny * nz;
  const double h = 0.02;
  Springs s(n, h);
  std::mt19937_64 rng(5u);
  std::uniform_real_distribution<double> u(0.7, 1.3);
  auto id = [&](int i, int j, int k) {
    return (i * ny + j) * nz + k;
  };
  for (int i = 0; i < nx; i++)
    for (int j = 0; j < ny; j++)
      for (int k = 0; k < nz; k++) {
        const int p = id(i, j, k);
        s.y.rows[p][0] = i;
        s.y.rows[p][1] = j;
        s.y.rows[p][2] = k;
        s.set_density(p, u(rng));
        s.set_volume(p, u(rng));
        if (i == 0) s.pin(p);
      }
  for (int p = 0; p < n; p++)
    for (int q = p + 1; q < n; q++) {
      double r2 = 0.0;
      for (int k = 0; k < 3; k++) r2 += std::pow(s.y.rows[q][k] - s.y.rows[p][k], 2);
      if (r2 < 2.01) s.spring(p, q, 50.0 / (h * h), std::sqrt(r2));
    }
  s.g[1] = 3.0;
  s.g[2] = -10.0;
  s.begin();
  BlockPreconditioner pc;
  KrylovTables kt(n);
  const SolveResult r = solve_newton_krylov(s, pc, 300, kt.work());
  ASSERT_TRUE(r.converged()) << r.measure;
  const std::vector<double> y = s.y.data;
  s.evaluate(true);
  EXPECT_LE(scaled_max(s, s.residual(), true), r.tolerance * 1.0001);
  sissm_sweep(s, true, SweepMemory());
  double moved = 0.0;
  for (size_t k = 0; k < y.size(); k++) moved = std::max(moved, std::fabs(s.y.data[k] - y[k]));
  EXPECT_LT(moved, 1e-8);
}

// A free body (no pins, no body force) with random velocities, solved with a budget far too
// small to converge: the truncated step changes the momentum; balance_momentum restores
// P^{n+1} = P^n and L^{n+1} = L^n (no external force) to round-off, and moves the body rigidly
// (every spring length unchanged).
TEST(Momentum, TruncatedSolveKeepsMomentumAfterTheBalance)
{
  const int n = 10;
  const double h = 0.05;
  Springs s(n, h);
  random_cluster(s, n, h, 9u);
  auto momenta = [&](Table &vel, Table &pos, double P[3], double L[3]) {
    double m = 0.0, c[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
      const double mi = s.rows().density[i] * s.rows().volume[i];
      m += mi;
      for (int k = 0; k < 3; k++) c[k] += mi * pos.rows[i][k];
    }
    for (int k = 0; k < 3; k++) {
      c[k] /= m;
      P[k] = L[k] = 0.0;
    }
    for (int i = 0; i < n; i++) {
      const double mi = s.rows().density[i] * s.rows().volume[i];
      const Eigen::Vector3d q(pos.rows[i][0] - c[0], pos.rows[i][1] - c[1], pos.rows[i][2] - c[2]);
      const Eigen::Vector3d vv(vel.rows[i][0], vel.rows[i][1], vel.rows[i][2]);
      const Eigen::Vector3d l = mi * q.cross(vv);
      for (int k = 0; k < 3; k++) {
        P[k] += mi * vel.rows[i][k];
        L[k] += l(k);
      }
    }
  };
  double P0[3], L0[3];
  momenta(s.v, s.y, P0, L0);
  s.begin();
  BlockPreconditioner pc;
  KrylovTables kt(n);
  const SolveResult r = solve_newton_krylov(s, pc, 3, kt.work());
  EXPECT_FALSE(r.converged());

  // without the balance the truncated step has picked up momentum
  {
    Table v1(n);
    for (int i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) v1.rows[i][k] = (s.y.rows[i][k] - s.yn.rows[i][k]) / h;
    double P1[3], L1[3];
    momenta(v1, s.y, P1, L1);
    double dp = 0.0;
    for (int k = 0; k < 3; k++) dp = std::max(dp, std::fabs(P1[k] - P0[k]));
    EXPECT_GT(dp, 1e-6);
  }
  std::vector<double> len0;
  for (int i = 0; i + 1 < n; i++) {
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) r2 += std::pow(s.y.rows[i + 1][k] - s.y.rows[i][k], 2);
    len0.push_back(std::sqrt(r2));
  }
  Table moment(n, kMomentumColumns);
  SerialReductions red(n);
  balance_momentum(s.rows(), red, {h, h * h, true}, s.y.ptr(), s.yn.ptr(), s.yhat.ptr(), nullptr,
                   moment.ptr());
  s.finish();
  // P^{n+1} = sum m v^{n+1}; L^{n+1} = (1/h) sum m q^n x r = sum m q^n x v^{n+1} (about the
  // centre of mass at the start: sum m q^n = 0)
  double P1[3], L1[3];
  momenta(s.v, s.yn, P1, L1);
  double pscale = 0.0, lscale = 0.0;
  for (int k = 0; k < 3; k++) {
    pscale = std::max(pscale, std::fabs(P0[k]));
    lscale = std::max(lscale, std::fabs(L0[k]));
  }
  for (int k = 0; k < 3; k++) {
    EXPECT_NEAR(P1[k], P0[k], 1e-12 * (pscale + 1.0));
    EXPECT_NEAR(L1[k], L0[k], 1e-10 * (lscale + 1.0));
  }
  for (int i = 0; i + 1 < n; i++) {
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) r2 += std::pow(s.y.rows[i + 1][k] - s.y.rows[i][k], 2);
    EXPECT_NEAR(std::sqrt(r2), len0[i], 1e-12 * len0[i]);
  }
}

// Rows outside the group (held atoms) take no part: their y^n, yhat and y are not set by the
// step (left as NaN here, as memory may hold), and the balance of the group's rows is the same
// as with those rows zero, and finite. (It once summed them as 0 x y^n: a NaN left in memory
// made the centre of mass garbage, to which the balance is invariant but for round-off, so runs
// of fix sissm with held atoms differed in their last digits from build to build; this test
// does not see that round-off, only a NaN that would reach the positions.)
TEST(Momentum, RowsOutsideTheGroupAreIgnored)
{
  const int n = 4;
  const int mask[n] = {1, 0, 1, 1};
  const double rho[n] = {2.0, 3.0, 1.5, 1.0}, vol[n] = {0.5, 1.0, 1.0, 2.0};
  Rows rows;
  rows.n = n;
  rows.mask = mask;
  rows.bit = 1;
  rows.volume = vol;
  rows.density = rho;
  const double h = 0.01;
  auto run = [&](double outside) {
    Table x(n), yn(n), yhat(n), moment(n, kMomentumColumns);
    for (int i = 0; i < n; i++)
      for (int k = 0; k < 3; k++) {
        const bool in = mask[i] != 0;
        yn.rows[i][k] = in ? 0.1 * (i + 1) + 0.03 * k : outside;
        yhat.rows[i][k] = in ? yn.rows[i][k] + h * (0.2 * k - 0.1 * i) : outside;
        x.rows[i][k] = in ? yhat.rows[i][k] + 1e-3 * (k - i) : outside;
      }
    SerialReductions red(n);
    balance_momentum(rows, red, {h, h * h, true}, x.ptr(), yn.ptr(), yhat.ptr(), nullptr,
                     moment.ptr());
    return x;
  };
  const Table zero = run(0.0), nan = run(std::numeric_limits<double>::quiet_NaN());
  for (int i = 0; i < n; i++) {
    if (!mask[i]) continue;
    for (int k = 0; k < 3; k++) {
      EXPECT_TRUE(std::isfinite(nan.rows[i][k]));
      EXPECT_EQ(nan.rows[i][k], zero.rows[i][k]);
    }
  }
}

TEST(Solvers, FirstNonFiniteRowOfTheGroup)
{
  const int mask[3] = {0, 1, 1};
  Rows rows;
  rows.n = 3;
  rows.mask = mask;
  rows.bit = 1;
  double d[3][3] = {{std::nan(""), 0, 0}, {1, 2, 3}, {4, 5, 6}};
  double *y[3] = {d[0], d[1], d[2]};
  EXPECT_EQ(first_nonfinite(rows, y), -1);    // row 0 is outside the group
  d[2][1] = INFINITY;
  EXPECT_EQ(first_nonfinite(rows, y), 2);
  d[1][0] = 1e308;
  d[1][1] = 1e308;    // each finite, their sum not
  EXPECT_EQ(first_nonfinite(rows, y), 1);
}

}    // namespace
