// The backward-Euler time scheme (doc/theory.rst, "The implicit step"):
//   r_i(y) = rho_i (yhat_i - y_i) + h^2 f_i(y) = 0,   yhat_i = y_i^n + h v_i^n (+ h^2 f_lag / rho)
//   D_i = rho_i I + h^2 K_i   (K_i the force model's diagonal stiffness block)
//   v^{n+1} = (y^{n+1} - y^n) / h
// The iteration starts at y^0 = y^n + h v^n (an equilibrium is a fixed point for any iteration
// count). First order, no history; it damps every mode with h omega >~ 1.

#ifndef PERISISSM_SOLVERS_BACKWARD_EULER_H
#define PERISISSM_SOLVERS_BACKWARD_EULER_H

#include "solvers/time_scheme.h"

namespace PeriSISSM {

class BackwardEuler : public TimeScheme {
 public:
  std::string name() const override { return "euler"; }
  void set_step(double h) override
  {
    h_ = h;
    c_ = h * h;
  }
  void begin(const Rows &rows, const StepArrays &a) override;
  void iterate_velocity(int i, const StepArrays &a, double *vel) const override
  {
    const double hinv = 1.0 / h_;
    for (int k = 0; k < 3; k++) vel[k] = (a.y[i][k] - a.yn[i][k]) * hinv;
  }
  void finish(const Rows &rows, const StepArrays &a) override;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_BACKWARD_EULER_H
