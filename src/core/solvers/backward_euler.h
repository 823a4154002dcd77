// The backward-Euler time scheme of an implicit step (doc/theory.rst, "The implicit step"):
//   r_i(y) = rho_i (yhat_i - y_i) + h^2 f_i(y) = 0,   yhat_i = y_i^n + h v_i^n (+ h^2 f_lag / rho)
//   J_i = rho_i I + h^2 K_i   (K_i the force model's diagonal stiffness block)
//   v^{n+1} = (y^{n+1} - y^n) / h
// The iteration starts at y^0 = y^n + h v^n (an equilibrium is a fixed point for any iteration
// count). A second-order scheme replaces this class and keeps the solvers.

#ifndef PERISISSM_SOLVERS_BACKWARD_EULER_H
#define PERISISSM_SOLVERS_BACKWARD_EULER_H

#include "solvers/system.h"

namespace PeriSISSM {

class BackwardEuler {
 public:
  // Start of a step for the unknown rows: yn = y, yhat = y + h v (plus h^2 (fa - fb) / rho
  // when fa is given: a force lagged from the previous step), y = y + h v.
  static void begin(const Rows &rows, double h, double **y, double **v, double **fa,
                    double **fb, double **yn, double **yhat);
  // residual of one row
  static inline void residual(double rho, const double *yhat, const double *y, const double *f,
                              double h2, double *r)
  {
    for (int k = 0; k < 3; k++) r[k] = rho * (yhat[k] - y[k]) + h2 * f[k];
  }
  // block of one row from the force model's stiffness block K (xx yy zz xy xz yz)
  static inline void block(double rho, double h2, const double *K, double D[6])
  {
    for (int k = 0; k < 6; k++) D[k] = (k < 3 ? rho : 0.0) + h2 * K[k];
  }
  // end of a step: v = (y - yn) / h for the unknown rows
  static void finish(const Rows &rows, double h, double **y, double **yn, double **v);
};

}  // namespace PeriSISSM

#endif  // PERISISSM_SOLVERS_BACKWARD_EULER_H
