// Generalized-alpha (see generalized_alpha.h).

#include "solvers/generalized_alpha.h"

namespace PeriSISSM {

GeneralizedAlpha::GeneralizedAlpha(double rho_inf) : rho_inf_(rho_inf)
{
  set_forces_at_end(false);
}

void GeneralizedAlpha::set_forces_at_end(bool on)
{
  const double rho = rho_inf_;
  alpha_m_ = on ? (rho - 1.0) / (rho + 1.0) : (2.0 * rho - 1.0) / (rho + 1.0);
  alpha_f_ = on ? 0.0 : rho / (rho + 1.0);
  gamma_ = 0.5 - alpha_m_ + alpha_f_;
  const double s = 1.0 - alpha_m_ + alpha_f_;
  beta_ = 0.25 * s * s;
  if (h_ > 0.0) set_step(h_);
}

void GeneralizedAlpha::set_step(double h)
{
  h_ = h;
  c_ = beta_ * h * h * (1.0 - alpha_f_) / (1.0 - alpha_m_);
}

void GeneralizedAlpha::begin(const Rows &rows, const StepArrays &a)
{
  const double h = h_, wf = 1.0 - alpha_f_;
  const double ka = h * h * (0.5 - beta_ - beta_ * alpha_m_ / (1.0 - alpha_m_));
  const bool mean = error_rule_ && alpha_f_ > 0.0;    // (generalized_alpha.h)
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    double *y = a.y[i], *hist = a.hist[i];
    const double *v = a.v[i];
    if (hist[6] < 1.0) {
      for (int k = 0; k < 3; k++) hist[k] = a.fstart[i][k] / rows.density[i];
      hist[6] = 1.0;
    }
    const double older = mean && hist[6] >= 2.0 ? 0.5 : 0.0;    // the weight of a^{n-1}
    for (int k = 0; k < 3; k++) {
      a.yn[i][k] = y[k];
      a.vn[i][k] = v[k];
      const double step = wf * (h * v[k] + ka * hist[k]);
      a.yhat[i][k] = y[k] + step;
      if (a.flag) a.yhat[i][k] += c_ * a.flag[i][k] / rows.density[i];
      // the first iterate: the predictor plus c times the guessed acceleration, exact where
      // the acceleration does not change (free fall: one evaluation)
      const double guess = (1.0 - older) * hist[k] + older * hist[3 + k];
      y[k] += step + (extrapolate_ ? c_ * guess : 0.0);
    }
  }
}

void GeneralizedAlpha::end_state(int i, int k, const StepArrays &a, double &acc, double &vel) const
{
  const double h = h_, an = a.hist[i][k], vn = a.vn[i][k];
  const double dy = (a.y[i][k] - a.yn[i][k]) / (1.0 - alpha_f_);    // y^{n+1} - y^n
  acc = (dy - h * vn - h * h * (0.5 - beta_) * an) / (beta_ * h * h);
  vel = vn + h * ((1.0 - gamma_) * an + gamma_ * acc);
}

void GeneralizedAlpha::iterate_velocity(int i, const StepArrays &a, double *vel) const
{
  for (int k = 0; k < 3; k++) {
    double acc, v1;
    end_state(i, k, a, acc, v1);
    vel[k] = (1.0 - alpha_f_) * v1 + alpha_f_ * a.vn[i][k];
  }
}

void GeneralizedAlpha::finish(const Rows &rows, const StepArrays &a)
{
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int k = 0; k < 3; k++) {
      double acc, v1;
      end_state(i, k, a, acc, v1);
      a.y[i][k] = a.yn[i][k] + (a.y[i][k] - a.yn[i][k]) / (1.0 - alpha_f_);
      a.hist[i][3 + k] = a.hist[i][k];
      a.hist[i][k] = acc;
      a.v[i][k] = v1;
    }
    a.hist[i][6] = 2.0;
  }
}

}    // namespace PeriSISSM
