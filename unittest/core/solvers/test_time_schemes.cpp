// The time schemes (backward Euler, BDF2, generalized-alpha) on toy systems without LAMMPS:
// exactness for free fall, order of convergence on a nonlinear swinging chain, the linear
// oscillator's amplitude and period per step against the schemes' characteristic roots, energy
// behaviour of generalized-alpha, variable steps of BDF2, the momentum balance of truncated
// steps, the generalized-alpha step against Chung and Hulbert's equations, and its first iterate.

#include "solvers/springs.h"

#include "solvers/momentum.h"
#include "solvers/preconditioner.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace PeriSISSM;
using namespace PeriSISSMTest;

// one converged step of s (Newton-Krylov with the block preconditioner)
void step(Springs &s, int budget = 200)
{
  s.begin();
  BlockPreconditioner pc;
  KrylovTables kt(s.rows().n);
  const SolveResult r = solve_newton_krylov(s, pc, budget, kt.work());
  ASSERT_TRUE(r.converged()) << "measure " << r.measure;
  s.finish();
}

std::unique_ptr<TimeScheme> scheme(const std::string &name, double rho_inf = 1.0)
{
  return make_time_scheme(name, rho_inf);
}

struct Variant {
  const char *name;
  double rho_inf;
};
const Variant kSchemes[] = {
    {"euler", 1.0}, {"bdf2", 1.0}, {"genalpha", 1.0}, {"genalpha", 0.5}, {"genalpha", 0.0}};

TEST(TimeSchemes, ByName)
{
  EXPECT_EQ(make_time_scheme("euler")->name(), "euler");
  EXPECT_EQ(make_time_scheme("bdf2")->name(), "bdf2");
  EXPECT_EQ(make_time_scheme("genalpha", 0.3)->name(), "genalpha");
  EXPECT_EQ(make_time_scheme("newmark"), nullptr);
  // BDF2 at a constant step: c = (2h/3)^2; generalized-alpha at rho_inf = 1: c = h^2/4
  auto b = make_time_scheme("bdf2");
  b->set_step(0.3);
  EXPECT_DOUBLE_EQ(b->force_factor(), 0.04);    // the first step restarts at w = 1
  auto g = make_time_scheme("genalpha", 1.0);
  g->set_step(0.3);
  EXPECT_DOUBLE_EQ(g->force_factor(), 0.0225);
  EXPECT_DOUBLE_EQ(g->force_time(), 0.5);
}

// A particle under a constant force density and an initial velocity: the second-order schemes
// are exact for a constant acceleration (BDF2 from its started history, generalized-alpha from
// a^0 = g), so 40 steps end on y0 + v0 t + g t^2 / 2 to round-off; backward Euler ends on its
// own closed form y0 + n h v0 + g h^2 n (n + 1) / 2.
TEST(TimeSchemes, FreeFallIsExact)
{
  for (const Variant &sv : kSchemes) {
    const bool euler = std::string(sv.name) == "euler";
    const double h = 0.05;
    Springs s(1, h, scheme(sv.name, sv.rho_inf));
    s.g[0] = 1.0;
    s.g[2] = -9.81;
    s.set_density(0, 2.0);
    const double y0[3] = {0.3, -0.2, 1.0}, v0[3] = {0.5, 1.5, 2.0};
    for (int k = 0; k < 3; k++) {
      s.y.rows[0][k] = y0[k];
      s.v.rows[0][k] = v0[k];
    }
    s.tol = 1e-14;
    for (int n = 0; n < 40; n++) step(s);
    const double t = 40 * h;
    for (int k = 0; k < 3; k++) {
      const double a = s.g[k] / 2.0;
      const double drop = euler ? 0.5 * a * h * h * 40 * 41 : 0.5 * a * t * t;
      EXPECT_NEAR(s.y.rows[0][k], y0[k] + v0[k] * t + drop, 1e-12) << sv.name << " " << sv.rho_inf;
      EXPECT_NEAR(s.v.rows[0][k], v0[k] + a * t, 1e-11) << sv.name << " " << sv.rho_inf;
    }
  }
}

// Generalized-alpha starts each step at constant acceleration: once a^n = g (from the first
// step on), a free fall meets a tight tolerance at the first evaluation of every step.
TEST(TimeSchemes, GeneralizedAlphaFreeFallTakesOneEvaluation)
{
  for (double rho_inf : {1.0, 0.8, 0.0}) {
    Springs s(1, 0.05, scheme("genalpha", rho_inf));
    s.g[2] = -9.81;
    s.v.rows[0][0] = 0.7;
    s.tol = 1e-12;
    for (int n = 0; n < 5; n++) {
      step(s);
      EXPECT_EQ(s.evaluations(), 1) << rho_inf << " step " << n;
    }
    // without extrapolation (after an unconverged step) it starts from the predictor
    s.scheme().set_extrapolation(false);
    step(s);
    EXPECT_GT(s.evaluations(), 1) << rho_inf;
  }
}

// The swinging chain (springs.h) over t = 0.8, at h = 0.005,
// 0.0025, 0.00125, against the same scheme at h = 0.8 / 5120: the error at the end falls by 2 per
// halving for backward Euler and by 4 for the second-order schemes (within 15%; the fastest
// mode has h omega = 0.07 at the largest step: BDF2 is still pre-asymptotic at h omega ~ 0.5,
// where its error ratios were 1.6 and 2.2, and 3.7 and 3.9 from h = 0.005 on).
double chain_end(const Variant &sv, double h, int steps)
{
  Springs s(3, h, scheme(sv.name, sv.rho_inf));
  swinging_chain(s);
  s.tol = 1e-14;
  for (int n = 0; n < steps; n++) step(s);
  return s.y.rows[2][1] + s.y.rows[2][2] + 0.5 * s.y.rows[2][0];
}

TEST(TimeSchemes, OrderOfConvergence)
{
  for (const Variant &sv : {kSchemes[0], kSchemes[1], kSchemes[2], kSchemes[3]}) {
    const double T = 0.8;
    const double ref = chain_end(sv, T / 5120, 5120);
    double err[3];
    for (int l = 0; l < 3; l++) {
      const int n = 160 << l;
      err[l] = std::fabs(chain_end(sv, T / n, n) - ref);
    }
    const double order = (std::string(sv.name) == "euler") ? 2.0 : 4.0;
    for (int l = 0; l < 2; l++)
      EXPECT_NEAR(err[l] / err[l + 1], order, 0.15 * order)
          << sv.name << " " << sv.rho_inf << ": errors " << err[0] << " " << err[1] << " "
          << err[2];
  }
}

// A linear oscillator: a particle tied to a fixed point by a linear spring (force -k u at any
// displacement), omega^2 = k / (rho V). Runs of 300 steps; after the start (60 steps: the
// spurious roots have decayed) the sequence u_n obeys u_{n+1} = p u_n - q u_{n-1} with
// p = 2 Re z, q = |z|^2 of the principal root z of the scheme's characteristic polynomial; the
// least-squares p, q give the amplitude per step |z| and the phase per step arg z, compared
// with the roots computed here from the schemes' defining equations (to 1e-9).
struct Oscillator {
  Springs s;
  Oscillator(const Variant &sv, double h, double omega) : s(1, h, scheme(sv.name, sv.rho_inf))
  {
    const double p[3] = {1.0, 0.0, 0.0};
    s.anchor(0, omega * omega, p);
    s.y.rows[0][0] = 1.0 + 0.01;    // displaced by 0.01
    tolerance(h, omega);
  }
  // the measure's round-off floor grows with c omega^2 (stiff steps)
  void tolerance(double h, double omega) { s.tol = 1e-15 * (1.0 + h * h * omega * omega); }
  double u() const { return s.y.rows[0][0] - 1.0; }
  double energy(double omega) const
  {
    const double v = s.v.rows[0][0];
    return 0.5 * v * v + 0.5 * omega * omega * u() * u();
  }
};

// principal root of BDF2 applied to q' = i omega q: (3/2 - i h omega) z^2 - 2 z + 1/2 = 0
std::complex<double> bdf2_root(double x)
{
  const std::complex<double> a(1.5, -x), b(-2.0, 0.0), c(0.5, 0.0);
  const std::complex<double> d = std::sqrt(b * b - 4.0 * a * c);
  const std::complex<double> z1 = (-b + d) / (2.0 * a), z2 = (-b - d) / (2.0 * a);
  return std::abs(z1) > std::abs(z2) ? z1 : z2;
}

// Chung-Hulbert amplification matrix of (u, h v, h^2 a) for u'' = -omega^2 u, from the defining
// equations (generalized_alpha.h), x = h omega
Eigen::Matrix3d alpha_matrix(double am, double af, double x)
{
  const double g = 0.5 - am + af, b = 0.25 * (1 - am + af) * (1 - am + af);
  // unknowns (u1, V1 = h v1, A1 = h^2 a1) from (u0, V0, A0):
  //   (1-am) A1 + am A0 + x^2 ((1-af) u1 + af u0) = 0
  //   u1 - b A1 = u0 + V0 + (1/2 - b) A0
  //   V1 - g A1 = V0 + (1 - g) A0
  Eigen::Matrix3d L, R;
  L << x * x * (1 - af), 0, 1 - am, 1, 0, -b, 0, 1, -g;
  R << -x * x * af, 0, -am, 1, 1, 0.5 - b, 0, 1, 1 - g;
  return L.inverse() * R;
}

Eigen::Matrix3d genalpha_matrix(double rho_inf, double x)
{
  return alpha_matrix((2 * rho_inf - 1) / (rho_inf + 1), rho_inf / (rho_inf + 1), x);
}

// the member of Wood, Bossak and Zienkiewicz: alpha_f = 0
Eigen::Matrix3d bossak_matrix(double rho_inf, double x)
{
  return alpha_matrix((rho_inf - 1) / (rho_inf + 1), 0.0, x);
}

std::complex<double> genalpha_root(double rho_inf, double x)
{
  const Eigen::Vector3cd ev = genalpha_matrix(rho_inf, x).eigenvalues();
  std::complex<double> best = ev(0);
  for (int k = 1; k < 3; k++)
    if (std::fabs(ev(k).imag()) > std::fabs(best.imag())) best = ev(k);
  return best;
}

TEST(TimeSchemes, LinearOscillatorAmplitudeAndPeriod)
{
  const double omega = 2.0;
  for (double x : {0.1, 0.3, 0.8}) {
    for (const Variant &sv : {kSchemes[1], kSchemes[2], kSchemes[3]}) {
      const double h = x / omega;
      Oscillator o(sv, h, omega);
      std::vector<double> u;
      for (int n = 0; n < 300; n++) {
        step(o.s);
        u.push_back(o.u());
      }
      // least squares u_{n+1} = p u_n - q u_{n-1}, n >= 60
      Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
      Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
      for (size_t n = 61; n + 1 < u.size(); n++) {
        const Eigen::Vector2d row(u[n], -u[n - 1]);
        A += row * row.transpose();
        rhs += row * u[n + 1];
      }
      const Eigen::Vector2d pq = A.ldlt().solve(rhs);
      const double amp = std::sqrt(pq(1)), phase = std::acos(pq(0) / (2.0 * amp));
      const std::complex<double> z = std::string(sv.name) == "bdf2" ? bdf2_root(x)
                                                                    : genalpha_root(sv.rho_inf, x);
      EXPECT_NEAR(amp, std::abs(z), 1e-9) << sv.name << " " << sv.rho_inf << " x " << x;
      EXPECT_NEAR(phase, std::fabs(std::arg(z)), 1e-9)
          << sv.name << " " << sv.rho_inf << " x " << x;
      // both second order: the period error is O(x^2) (relative, below x^2 / 2 here) and
      // the amplitude loss per period O(x^3) at most
      const double period_error = x / std::fabs(std::arg(z)) - 1.0;
      EXPECT_LT(std::fabs(period_error), 0.5 * x * x);
      const double loss_per_period = 1.0 - std::pow(amp, 2.0 * M_PI / phase);
      EXPECT_GE(loss_per_period, -1e-9);
      EXPECT_LT(loss_per_period, 2.0 * M_PI * x * x * x);
    }
  }
}

// Generalized-alpha with rho_inf = 1 keeps a linear oscillator's energy (started from the
// consistent a^0 it is the trapezoidal rule: to the solver tolerance over 2000 steps at
// h omega = 0.5 and 5); rho_inf < 1 damps only what the step does not resolve: the energy lost
// per period falls like (h omega)^3 (x 8 per halving, within 25%; measured 7.7e-4, 2.9e-5 and
// 1e-6 per period at h omega = 0.05 for rho_inf = 0, 0.5, 0.8), while the spectral radius of the
// step tends to rho_inf as h omega grows (the three roots meet at -rho_inf: within
// 1.5 (h omega)^(-2/3), 1% at 1000) and 100 steps at h omega = 1000 take the energy below
// (rho_inf + 0.1)^200 of its start.
double energy_loss_per_period(double rho_inf, double x, double omega)
{
  Oscillator o({"genalpha", rho_inf}, x / omega, omega);
  const double e0 = o.energy(omega);
  const int per_period = (int) std::lround(2.0 * M_PI / x);
  for (int n = 0; n < 3 * per_period; n++) step(o.s);
  return (e0 - o.energy(omega)) / e0 / 3.0;
}

TEST(TimeSchemes, GeneralizedAlphaEnergy)
{
  const double omega = 3.0;
  for (double x : {0.5, 5.0}) {
    Oscillator o(kSchemes[2], x / omega, omega);
    const double e0 = o.energy(omega);
    double worst = 0.0;
    for (int n = 0; n < 2000; n++) {
      step(o.s);
      worst = std::max(worst, std::fabs(o.energy(omega) - e0) / e0);
    }
    EXPECT_LT(worst, 1e-9) << "h omega " << x;
  }
  for (double rho_inf : {0.0, 0.5, 0.8}) {
    const double l1 = energy_loss_per_period(rho_inf, 0.05, omega);
    const double l2 = energy_loss_per_period(rho_inf, 0.025, omega);
    EXPECT_GT(l2, 0.0) << "rho_inf " << rho_inf;
    EXPECT_NEAR(l1 / l2, 8.0, 2.0) << "rho_inf " << rho_inf << ": " << l1 << " " << l2;
    for (double x : {1e3, 1e7})
      EXPECT_NEAR(genalpha_matrix(rho_inf, x).eigenvalues().cwiseAbs().maxCoeff(), rho_inf,
                  1.5 * std::pow(x, -2.0 / 3.0))
          << "rho_inf " << rho_inf << " h omega " << x;
    const double x = 1000.0;
    Oscillator o({"genalpha", rho_inf}, x / omega, omega);
    const double e0 = o.energy(omega);
    for (int n = 0; n < 100; n++) step(o.s);
    EXPECT_LT(o.energy(omega) / e0, std::pow(rho_inf + 0.1, 200)) << "rho_inf " << rho_inf;
  }
}

// One step of the oscillator o (step h, h omega = x) from the state (u, 0.2, 0.05) (a^n not the
// consistent -omega^2 u) against the step of the amplification matrix A to round-off.
void expect_step_is(Oscillator &o, double h, const Eigen::Matrix3d &A, const std::string &what)
{
  o.s.v.rows[0][0] = 0.2;
  o.s.hist.rows[0][0] = 0.05;    // a^n
  o.s.hist.rows[0][6] = 1.0;     // a^n valid, a^{n-1} not
  const Eigen::Vector3d s0(o.u(), h * 0.2, h * h * 0.05);
  step(o.s);
  const Eigen::Vector3d s1 = A * s0;
  // the solve is exact to its tolerance in u, and a^{n+1} divides it by beta
  const double tol = 50.0 * o.s.tol + 1e-14 * s0.norm();
  EXPECT_NEAR(o.u(), s1(0), tol) << what;
  EXPECT_NEAR(h * o.s.v.rows[0][0], s1(1), tol) << what;
  EXPECT_NEAR(h * h * o.s.hist.rows[0][0], s1(2), tol) << what;
}

// One generalized-alpha step of the linear oscillator from a state (u, v, a) that is not
// consistent (a != -omega^2 u) equals the Chung-Hulbert map to round-off.
TEST(TimeSchemes, GeneralizedAlphaIsChungHulbert)
{
  const double omega = 2.5;
  for (double rho_inf : {0.0, 0.3, 0.9, 1.0})
    for (double x : {0.7, 1000.0}) {
      const double h = x / omega;
      Oscillator o({"genalpha", rho_inf}, h, omega);
      expect_step_is(o, h, genalpha_matrix(rho_inf, x),
                     std::to_string(rho_inf) + " " + std::to_string(x));
    }
}

// With the forces at the end of the step (set_forces_at_end, for a contact that checks the
// moves of the unknowns) a generalized-alpha step is Wood, Bossak and Zienkiewicz's (alpha_f =
// 0, alpha_m = (rho_inf - 1) / (rho_inf + 1)) to round-off, evaluates at t^{n+1}, keeps the
// spectral radius rho_inf at h omega -> infinity (within 1.5 (h omega)^(-2/3), as above) and
// stays second order (period error below (h omega)^2 / 2 at h omega = 0.1 and 0.3); switched
// off again it is Chung and Hulbert's.
TEST(TimeSchemes, GeneralizedAlphaWithForcesAtTheEndIsBossak)
{
  const double omega = 2.5;
  for (double rho_inf : {0.0, 0.5, 0.8, 1.0}) {
    for (double x : {0.1, 0.3, 0.7, 1000.0}) {
      const double h = x / omega;
      Oscillator o({"genalpha", rho_inf}, h, omega);
      o.s.scheme().set_forces_at_end(true);
      EXPECT_EQ(o.s.scheme().force_time(), 1.0);
      expect_step_is(o, h, bossak_matrix(rho_inf, x),
                     std::to_string(rho_inf) + " " + std::to_string(x));
      if (x < 0.5) {
        const Eigen::Vector3cd ev = bossak_matrix(rho_inf, x).eigenvalues();
        double phase = 0.0;
        for (int k = 0; k < 3; k++) phase = std::max(phase, std::fabs(std::arg(ev(k))));
        EXPECT_LT(std::fabs(x / phase - 1.0), 0.5 * x * x) << rho_inf << " " << x;
      }
    }
    for (double x : {1e3, 1e7})
      EXPECT_NEAR(bossak_matrix(rho_inf, x).eigenvalues().cwiseAbs().maxCoeff(), rho_inf,
                  1.5 * std::pow(x, -2.0 / 3.0))
          << "rho_inf " << rho_inf << " h omega " << x;
  }
  auto ga = make_time_scheme("genalpha", 0.8);
  ga->set_forces_at_end(true);
  ga->set_forces_at_end(false);
  EXPECT_NEAR(ga->force_time(), 1.0 - 0.8 / 1.8, 1e-15);
}

// The first iterate of a generalized-alpha step (generalized_alpha.h). On a mode far beyond the
// step (h omega = 1000), whose accelerations alternate in sign from step to step (the roots
// meet at -rho_inf), Chung and Hulbert's step with the error rule on starts from the mean of
// the last two accelerations: after 12 converged steps its first iterate is within 0.6 of the
// distance to the solved step that the last acceleration alone gives (measured 2e-4 of it at
// rho_inf = 1, 0.2 at 0.8). Without the error rule, with the forces at the end, in a first
// step (one acceleration known) it starts from the last acceleration; without extrapolation
// from the predictor itself.
TEST(TimeSchemes, GeneralizedAlphaFirstIterate)
{
  const double omega = 2.5, x = 1000.0, h = x / omega;
  for (double rho_inf : {1.0, 0.8})
    for (int variant = 0; variant < 3; variant++) {
      const bool at_end = variant == 1, rule = variant != 2, mean = rule && !at_end;
      Oscillator o({"genalpha", rho_inf}, h, omega);
      o.s.scheme().set_forces_at_end(at_end);
      o.s.scheme().set_error_rule(rule);
      const std::string what = std::to_string(rho_inf) + (at_end ? " at the end" : "") +
          (rule ? "" : " without the error rule");
      for (int n = 0; n < 12; n++) {
        o.s.begin();
        const double first = o.s.y.rows[0][0];
        const double an = o.s.hist.rows[0][0], older = o.s.hist.rows[0][3];
        const double c = o.s.scheme().force_factor();
        // the first iterate from a^n alone: the predictor plus c a^n
        const double from_an = o.s.yhat.rows[0][0] + c * an;
        BlockPreconditioner pc;
        KrylovTables kt(1);
        ASSERT_TRUE(solve_newton_krylov(o.s, pc, 200, kt.work()).converged()) << what;
        const double solved = o.s.y.rows[0][0];
        o.s.finish();
        const double roundoff = 1e-14 * std::fabs(first);
        if (n == 0 || !mean) {
          EXPECT_NEAR(first, from_an, roundoff) << what << " step " << n;
          continue;
        }
        EXPECT_NEAR(first, o.s.yhat.rows[0][0] + 0.5 * c * (an + older), roundoff) << what;
        if (n == 11) {
          std::printf("rho_inf %s: first iterate %.3g from the solved step, a^n's %.3g\n",
                      what.c_str(), std::fabs(first - solved), std::fabs(from_an - solved));
          EXPECT_LT(std::fabs(first - solved), 0.6 * std::fabs(from_an - solved)) << what;
        }
      }
    }
  // without extrapolation the first iterate is the predictor itself
  Oscillator o({"genalpha", 0.8}, h, omega);
  o.s.scheme().set_error_rule(true);
  for (int n = 0; n < 3; n++) step(o.s);
  o.s.scheme().set_extrapolation(false);
  o.s.begin();
  EXPECT_EQ(o.s.y.rows[0][0], o.s.yhat.rows[0][0]);
}

// BDF2 at variable steps (alternating h and h/2, w = 1/2 and 2) stays second order on the
// swinging chain (the restart after a step more than twice the last one is tested through
// LAMMPS: test_fix_sissm_schemes.py, cut-back steps).
TEST(TimeSchemes, Bdf2VariableSteps)
{
  const Variant sv = kSchemes[1];
  auto run = [&](double h, int pairs) {
    Springs s(3, h, scheme(sv.name));
    swinging_chain(s);
    s.tol = 1e-14;
    for (int n = 0; n < pairs; n++) {
      s.set_step(h);
      step(s);
      s.set_step(h / 2);
      step(s);
    }
    return s.y.rows[2][1] + s.y.rows[2][2] + 0.5 * s.y.rows[2][0];
  };
  const double T = 0.8;
  const double ref = chain_end(sv, T / 5120, 5120);
  double err[3];
  for (int l = 0; l < 3; l++) {
    const int pairs = 96 << l;    // 1.5 h per pair
    err[l] = std::fabs(run(T / (1.5 * pairs), pairs) - ref);
  }
  for (int l = 0; l < 2; l++) EXPECT_NEAR(err[l] / err[l + 1], 4.0, 0.6) << err[l];
}

// A free cluster with random velocities stepped by BDF2 and generalized-alpha with a budget too
// small to converge: after the balance the step satisfies what a converged step satisfies
// (sum m (y - yhat) = 0 and sum (y - c) x m (y - yhat) = 0 without external force) to
// round-off, and every spring length is unchanged by it (a rigid correction).
TEST(TimeSchemes, MomentumBalanceOfTruncatedSteps)
{
  for (const Variant &sv : {kSchemes[1], kSchemes[3]}) {
    const int n = 10;
    const double h = 0.05;
    Springs s(n, h, scheme(sv.name, sv.rho_inf));
    random_cluster(s, n, h, 5u);
    s.begin();
    BlockPreconditioner pc;
    KrylovTables kt(n);
    EXPECT_FALSE(solve_newton_krylov(s, pc, 3, kt.work()).converged());
    auto lengths = [&]() {
      std::vector<double> len;
      for (int i = 0; i + 1 < n; i++) {
        double r2 = 0.0;
        for (int k = 0; k < 3; k++) r2 += std::pow(s.y.rows[i + 1][k] - s.y.rows[i][k], 2);
        len.push_back(std::sqrt(r2));
      }
      return len;
    };
    const std::vector<double> len0 = lengths();
    Table moment(n, kMomentumColumns);
    SerialReductions red(n);
    const MomentumBalance mb{h, s.scheme().force_factor(), false};
    balance_momentum(s.rows(), red, mb, s.y.ptr(), s.yn.ptr(), s.yhat.ptr(), nullptr, moment.ptr());
    Eigen::Vector3d P = Eigen::Vector3d::Zero(), L = Eigen::Vector3d::Zero(),
                    c = Eigen::Vector3d::Zero(), scale = Eigen::Vector3d::Zero();
    double mass = 0.0;
    for (int i = 0; i < n; i++) {
      const double m = s.rows().density[i] * s.rows().volume[i];
      mass += m;
      for (int k = 0; k < 3; k++) c(k) += m * s.y.rows[i][k];
    }
    c /= mass;
    for (int i = 0; i < n; i++) {
      const double m = s.rows().density[i] * s.rows().volume[i];
      Eigen::Vector3d d, r;
      for (int k = 0; k < 3; k++) {
        d(k) = m * (s.y.rows[i][k] - s.yhat.rows[i][k]);
        r(k) = s.y.rows[i][k] - c(k);
      }
      P += d;
      L += r.cross(d);
      scale += (m * r.norm()) * Eigen::Vector3d::Ones() * h;
    }
    EXPECT_LT(P.norm(), 1e-13 * mass) << sv.name;
    EXPECT_LT(L.norm(), 1e-12 * scale.norm()) << sv.name;
    // the balance moved the body rigidly, and it did move it
    const std::vector<double> len1 = lengths();
    for (int i = 0; i + 1 < n; i++) EXPECT_NEAR(len1[i], len0[i], 1e-12 * len0[i]) << sv.name;
  }
}

TEST(TimeSchemes, ResidualsOfTheGroupStopAtTheFirstNonFinite)
{
  const auto be = scheme("euler");
  be->set_step(0.5);    // c = h^2 = 0.25
  const int mask[3] = {1, 0, 1};
  const double density[3] = {2.0, 3.0, 4.0};
  Rows rows;
  rows.n = 3;
  rows.mask = mask;
  rows.bit = 1;
  rows.density = density;
  double yhat_d[3][3] = {{1, 2, 3}, {0, 0, 0}, {1, 1, 1}};
  double y_d[3][3] = {{0, 0, 0}, {0, 0, 0}, {1, 1, 1}};
  double f_d[3][3] = {{4, 8, 12}, {1, 1, 1}, {1e200, 0, 0}};
  double r_d[3][3] = {{9, 9, 9}, {9, 9, 9}, {9, 9, 9}};
  double *yhat[3] = {yhat_d[0], yhat_d[1], yhat_d[2]}, *y[3] = {y_d[0], y_d[1], y_d[2]},
         *f[3] = {f_d[0], f_d[1], f_d[2]}, *r[3] = {r_d[0], r_d[1], r_d[2]};
  // row 2's residual 2.5e199 is finite, its square is not
  EXPECT_EQ(be->residuals(rows, yhat, y, f, r), 2);
  for (int k = 0; k < 3; k++) EXPECT_DOUBLE_EQ(r_d[0][k], 2.0 * (k + 1) + 0.25 * 4.0 * (k + 1));
  EXPECT_EQ(r_d[1][0], 9.0);    // outside the group: untouched
  f_d[2][0] = 1.0;
  EXPECT_EQ(be->residuals(rows, yhat, y, f, r), -1);
  EXPECT_DOUBLE_EQ(r_d[2][0], 0.25);
  f_d[0][1] = std::nan("");
  EXPECT_EQ(be->residuals(rows, yhat, y, f, r), 0);
}

}    // namespace
