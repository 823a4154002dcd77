// Toy nonlinear systems for the solver tests, without LAMMPS: particles joined by nonlinear
// springs under a constant body force, stepped by any time scheme (time_scheme.h) and solved by
// the SISSM Jacobi sweeps or Newton-Krylov.

#ifndef PERISISSM_TEST_SPRINGS_H
#define PERISISSM_TEST_SPRINGS_H

#include "linalg/reductions.h"
#include "solvers/backward_euler.h"
#include "solvers/newton_krylov.h"
#include "solvers/system.h"
#include "solvers/time_scheme.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

namespace PeriSISSMTest {

using namespace PeriSISSM;

// Rows of 3 doubles with row pointers (the layout LAMMPS gives per-atom arrays).
struct Table {
  explicit Table(int n, int width = 3) : data(n * width, 0.0), rows(n)
  {
    for (int i = 0; i < n; i++) rows[i] = data.data() + width * i;
  }
  std::vector<double> data;
  std::vector<double *> rows;
  double **ptr() { return rows.data(); }
};

// Particles i, j joined by springs of energy 1/2 k (|y_j - y_i| - L)^2, a constant body force
// density g, densities rho and volumes V, stepped by a time scheme (backward Euler unless
// another is given): r = rho (yhat - y) + c f(y), with f the force density; block = rho I +
// c sum_j k I (the spring stiffness along any direction at rest length, as the SISSM block
// takes it).
class Springs : public NonlinearSystem {
 public:
  Springs(int n, double h, std::unique_ptr<TimeScheme> scheme = nullptr) :
      n_(n), h_(h), y(n), v(n), yn(n), vn(n), yhat(n), res(n), fstart(n),
      hist(n, scheme ? std::max(scheme->history_columns(), 1) : 1), red_(n),
      scheme_(scheme ? std::move(scheme) : std::make_unique<BackwardEuler>())
  {
    mask_.assign(n, 1);
    rho_.assign(n, 1.0);
    vol_.assign(n, 1.0);
    kdiag_.assign(n, 0.0);
    rows_.n = n;
    rows_.mask = mask_.data();
    rows_.bit = 1;
    rows_.volume = vol_.data();
    rows_.density = rho_.data();
  }
  void spring(int i, int j, double k, double L)
  {
    springs_.push_back({i, j, k, L});
    kdiag_[i] += k;
    kdiag_[j] += k;
  }
  // a linear spring of energy 1/2 k |y_i - p|^2 to the fixed point p
  void anchor(int i, double k, const double p[3])
  {
    anchors_.push_back({i, k, {p[0], p[1], p[2]}});
    kdiag_[i] += k;
  }
  void pin(int i) { mask_[i] = 0; }
  void set_density(int i, double rho) { rho_[i] = rho; }
  void set_volume(int i, double vol) { vol_[i] = vol; }

  // the per-row arrays of a step
  StepArrays arrays()
  {
    StepArrays a;
    a.y = y.ptr();
    a.v = v.ptr();
    a.yn = yn.ptr();
    a.vn = vn.ptr();
    a.yhat = yhat.ptr();
    a.hist = hist.ptr();
    a.fstart = fstart.ptr();
    return a;
  }
  // start a step from y, v (fstart: the force density at y, for schemes that start a history)
  void begin()
  {
    scheme_->set_step(h_);
    if (scheme_->history_columns() > 0) { forces(fstart); }
    scheme_->begin(rows_, arrays());
    evals_ = 0;
  }
  void finish() { scheme_->finish(rows_, arrays()); }
  void set_step(double h) { h_ = h; }
  TimeScheme &scheme() { return *scheme_; }

  // the force density at the current positions
  void forces(Table &f) const
  {
    for (int i = 0; i < n_; i++)
      for (int k = 0; k < 3; k++) f.rows[i][k] = g[k];
    for (const auto &s : springs_) {
      double d[3], r2 = 0.0;
      for (int k = 0; k < 3; k++) {
        d[k] = y.rows[s.j][k] - y.rows[s.i][k];
        r2 += d[k] * d[k];
      }
      const double r = std::sqrt(r2), t = s.k * (r - s.L) / r;
      for (int k = 0; k < 3; k++) {
        f.rows[s.i][k] += t * d[k] / vol_[s.i];
        f.rows[s.j][k] -= t * d[k] / vol_[s.j];
      }
    }
    for (const auto &a : anchors_)
      for (int k = 0; k < 3; k++) f.rows[a.i][k] -= a.k * (y.rows[a.i][k] - a.p[k]) / vol_[a.i];
  }

  // NonlinearSystem
  const Rows &rows() const override { return rows_; }
  Reductions &reductions() override { return red_; }
  double **unknowns() override { return y.ptr(); }
  double **residual() override { return res.ptr(); }
  int evaluations() const override { return evals_; }
  bool evaluation_complete() const override { return true; }
  bool stalled() const override { return stall_from > 0 && evals_ >= stall_from; }
  double step_tolerance() override { return tol; }
  double **start() override { return yn.ptr(); }
  void check_finite() override
  {
    for (double d : y.data)
      if (!std::isfinite(d)) throw std::runtime_error("non-finite");
  }
  void evaluate(bool) override
  {
    evals_++;
    Table f(n_);
    forces(f);
    for (int i = 0; i < n_; i++)
      if (mask_[i]) scheme_->residual(rho_[i], yhat.rows[i], y.rows[i], f.rows[i], res.rows[i]);
  }
  void block(int i, double D[6]) const override
  {
    const double K[6] = {kdiag_[i] / vol_[i], kdiag_[i] / vol_[i], kdiag_[i] / vol_[i], 0, 0, 0};
    scheme_->block(rho_[i], K, D);
  }

  double tol = 1e-10;
  double g[3] = {0.0, 0.0, 0.0};
  int stall_from = 0;    // stalled() from this evaluation on (0: never)

 private:
  struct Spring {
    int i, j;
    double k, L;
  };
  struct Anchor {
    int i;
    double k, p[3];
  };
  int n_;
  double h_;

 public:
  Table y, v, yn, vn, yhat, res, fstart, hist;

 private:
  SerialReductions red_;
  std::unique_ptr<TimeScheme> scheme_;
  Rows rows_;
  std::vector<int> mask_;
  std::vector<double> rho_, vol_, kdiag_;
  std::vector<Spring> springs_;
  std::vector<Anchor> anchors_;
  int evals_ = 0;
};

// A free cluster of n particles with random positions, velocities, densities and volumes (from
// seed), each joined to its next two by springs stretched from 0.8 of their length (stiff: h^2 k
// / rho ~ 200), no pins and no body force.
inline void random_cluster(Springs &s, int n, double h, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.5, 1.5);
  for (int i = 0; i < n; i++) {
    for (int k = 0; k < 3; k++) {
      s.y.rows[i][k] = 2.0 * u(rng) + (k == 0 ? 1.3 * i : 0.0);
      s.v.rows[i][k] = u(rng);
    }
    s.set_density(i, w(rng));
    s.set_volume(i, w(rng));
  }
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < std::min(n, i + 3); j++) {
      double r2 = 0.0;
      for (int k = 0; k < 3; k++) r2 += std::pow(s.y.rows[j][k] - s.y.rows[i][k], 2);
      s.spring(i, j, 200.0 / (h * h), 0.8 * std::sqrt(r2));
    }
}

// A chain of three particles on stiff nonlinear springs (k = 50, rest length 1), pinned at one
// end, under a body force -2 along z, swinging from a sideways velocity (large rotations: the
// problem is nonlinear).
inline void swinging_chain(Springs &s)
{
  for (int i = 0; i < 3; i++) s.y.rows[i][0] = i;
  for (int i = 0; i + 1 < 3; i++) s.spring(i, i + 1, 50.0, 1.0);
  s.pin(0);
  s.g[2] = -2.0;
  s.v.rows[1][1] = 1.0;
  s.v.rows[2][1] = 2.0;
}

// a hanging chain of n particles, spacing 1, the first pinned, gravity along -z, stiff springs
// (h^2 k / rho = 400: far beyond an explicit step)
inline Springs chain(int n, double h)
{
  Springs s(n, h);
  for (int i = 0; i < n; i++) s.y.rows[i][0] = i;
  for (int i = 0; i + 1 < n; i++) s.spring(i, i + 1, 400.0 / (h * h), 1.0);
  s.pin(0);
  s.g[2] = -10.0;
  return s;
}

struct KrylovTables {
  explicit KrylovTables(int n) : xb(n), rb(n), jb(n), cr(n), zd(n), pd(n), sd(n), term(n) {}
  KrylovWork work()
  {
    KrylovWork w;
    w.xbase = xb.ptr();
    w.rbase = rb.ptr();
    w.jbase = jb.ptr();
    w.cres = cr.ptr();
    w.zdir = zd.ptr();
    w.pdir = pd.ptr();
    w.sdir = sd.ptr();
    w.term = term.data();
    return w;
  }
  Table xb, rb, jb, cr, zd, pd, sd;
  std::vector<double> term;
};

}    // namespace PeriSISSMTest

#endif    // PERISISSM_TEST_SPRINGS_H
