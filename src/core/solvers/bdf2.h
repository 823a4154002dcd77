// BDF2, the two-step backward differentiation formula, at variable steps (doc/theory.rst, "Time
// schemes"). With w = h_n / h_{n-1}, a0 = (1 + 2w) / (1 + w), a2 = w^2 / (1 + w), applied to
// positions and to velocities:
//   a0 (y^{n+1} - y^n) - a2 (y^n - y^{n-1}) = h v^{n+1}
//   a0 (v^{n+1} - v^n) - a2 (v^n - v^{n-1}) = h a^{n+1},   a^{n+1} = f(y^{n+1}) / rho
// Eliminating v^{n+1} gives the common problem rho (y - yhat) = c f(y) with
//   c    = (h / a0)^2
//   yhat = y^n + (a2/a0) Dy + (h/a0) (v^n + (a2/a0) Dv)     (Dy = y^n - y^{n-1}, Dv = v^n - v^{n-1})
// and at the end v^{n+1} = (a0 (y^{n+1} - y^n) - a2 Dy) / h. At a constant step (w = 1):
// c = (2h/3)^2, yhat = 4/3 y^n - 1/3 y^{n-1} + 2h/3 (4/3 v^n - 1/3 v^{n-1}). Second order and
// L-stable (it damps modes with h omega >> 1 completely, and slow ones at O((h omega)^3) per
// step).
// History per row (differences, so periodic images do not matter): Dy, Dv, a^n, the velocity
// the last step ended with, and the valid flag. Start (no history, after a restart from another
// scheme, a velocity changed between steps by another command, or a step more than twice the
// last one, where variable-step BDF2 loses zero-stability at w = 1 + sqrt 2): the
// history of a step of length h from v^n and a^n (a^n the last step's acceleration, or
// f(y^n) / rho for a row without history):
//   Dy = h v^n - h^2/2 a^n,   Dv = h a^n
// exact for constant acceleration (free fall stays exact), second order in general.

#ifndef PERISISSM_SOLVERS_BDF2_H
#define PERISISSM_SOLVERS_BDF2_H

#include "solvers/time_scheme.h"

namespace PeriSISSM {

class Bdf2 : public TimeScheme {
 public:
  // history columns: a^n (0-2), Dy (3-5), Dv (6-8), v^n as the last step left it (9-11),
  // valid (12)
  static constexpr int kColumns = 13;
  std::string name() const override { return "bdf2"; }
  int history_columns() const override { return kColumns; }
  void set_step(double h) override;
  void begin(const Rows &rows, const StepArrays &a) override;
  void iterate_velocity(int i, const StepArrays &a, double *vel) const override;
  void finish(const Rows &rows, const StepArrays &a) override;
  // the state: the length of the step the history belongs to (0: none)
  int state_size() const override { return 1; }
  void get_state(double *s) const override { s[0] = hprev_; }
  void set_state(const double *s) override { hprev_ = s[0]; }

 private:
  double hprev_ = 0.0;     // the step of the history (0: no step yet)
  bool restart_ = true;    // this step starts the history anew
  double a0_ = 1.5, a2_ = 0.5;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_BDF2_H
