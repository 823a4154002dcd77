// The backward-Euler time scheme (doc/theory.rst, "The implicit step"):
//   r_i(y) = rho_i (yhat_i - y_i) + h^2 f_i(y) = 0,   yhat_i = y_i^n + h v_i^n (+ h^2 f_lag / rho)
//   D_i = rho_i I + h^2 K_i   (K_i the force model's diagonal stiffness block)
//   v^{n+1} = (y^{n+1} - y^n) / h
// The iteration starts at y^0 = y^n + h v^n (an equilibrium is a fixed point for any iteration
// count). First order; it damps every mode with h omega >~ 1.

#ifndef PERISISSM_SOLVERS_BACKWARD_EULER_H
#define PERISISSM_SOLVERS_BACKWARD_EULER_H

#include "solvers/time_scheme.h"

namespace PeriSISSM {

class BackwardEuler : public TimeScheme {
 public:
  void set_step(double h) override
  {
    h_ = h;
    h2_ = h * h;
  }
  void begin(const Rows &rows, double **y, double **v, double **flag, double **yn,
             double **yhat) override;
  double force_factor() const override { return h2_; }
  void residual(double rho, const double *yhat, const double *y, const double *f,
                double *r) const override
  {
    for (int k = 0; k < 3; k++) r[k] = rho * (yhat[k] - y[k]) + h2_ * f[k];
  }
  void block(double rho, const double *K, double D[6]) const override
  {
    for (int k = 0; k < 6; k++) D[k] = (k < 3 ? rho : 0.0) + h2_ * K[k];
  }
  void finish(const Rows &rows, double **y, double **yn, double **v) const override;

 private:
  double h_ = 0.0, h2_ = 0.0;
};

}  // namespace PeriSISSM

#endif  // PERISISSM_SOLVERS_BACKWARD_EULER_H
