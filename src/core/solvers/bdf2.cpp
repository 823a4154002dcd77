// BDF2 at variable steps (see bdf2.h).

#include "solvers/bdf2.h"

namespace PeriSISSM {

void Bdf2::set_step(double h)
{
  h_ = h;
  // beyond a ratio of 2 the variable-step formula nears its zero-stability limit 1 + sqrt 2
  restart_ = !(hprev_ > 0.0) || h > 2.0 * hprev_;
  const double w = restart_ ? 1.0 : h / hprev_;
  a0_ = (1.0 + 2.0 * w) / (1.0 + w);
  a2_ = w * w / (1.0 + w);
  c_ = (h / a0_) * (h / a0_);
}

void Bdf2::begin(const Rows &rows, const StepArrays &a)
{
  const double h = h_, r = a2_ / a0_, g = h / a0_;
  // the step the history of a started row belongs to (see set_step)
  const double hs = restart_ ? h : hprev_;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    double *y = a.y[i], *hist = a.hist[i];
    const double *v = a.v[i];
    const bool valid = hist[12] == 1.0;
    if (restart_ || !valid || v[0] != hist[9] || v[1] != hist[10] || v[2] != hist[11]) {
      // the history of a step hs from v^n and a^n (kept, or f(y^n) / rho)
      if (!valid)
        for (int k = 0; k < 3; k++) hist[k] = a.fstart[i][k] / rows.density[i];
      for (int k = 0; k < 3; k++) {
        hist[3 + k] = hs * v[k] - 0.5 * hs * hs * hist[k];
        hist[6 + k] = hs * hist[k];
      }
      hist[12] = 1.0;
    }
    for (int k = 0; k < 3; k++) {
      a.yn[i][k] = y[k];
      a.vn[i][k] = v[k];
      const double step = r * hist[3 + k] + g * (v[k] + r * hist[6 + k]);
      a.yhat[i][k] = y[k] + step;
      if (a.flag) a.yhat[i][k] += c_ * a.flag[i][k] / rows.density[i];
      y[k] += step;
    }
  }
}

void Bdf2::iterate_velocity(int i, const StepArrays &a, double *vel) const
{
  for (int k = 0; k < 3; k++)
    vel[k] = (a0_ * (a.y[i][k] - a.yn[i][k]) - a2_ * a.hist[i][3 + k]) / h_;
}

void Bdf2::finish(const Rows &rows, const StepArrays &a)
{
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    double *hist = a.hist[i];
    for (int k = 0; k < 3; k++) {
      const double dy = a.y[i][k] - a.yn[i][k];
      const double v1 = (a0_ * dy - a2_ * hist[3 + k]) / h_;
      const double dv = v1 - a.vn[i][k];
      hist[k] = (a0_ * dv - a2_ * hist[6 + k]) / h_;
      hist[3 + k] = dy;
      hist[6 + k] = dv;
      hist[9 + k] = v1;
      a.v[i][k] = v1;
    }
  }
  hprev_ = h_;
}

}    // namespace PeriSISSM
