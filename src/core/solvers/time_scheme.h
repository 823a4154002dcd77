// The time scheme of an implicit step (doc/theory.rst, "The implicit step"): what the unknowns
// start from, the residual whose root the solvers find, the diagonal blocks of its Jacobian,
// and the velocities at the end. One force evaluation per residual; the solvers (jacobi.h,
// newton_krylov.h) do not know which scheme they solve.

#ifndef PERISISSM_SOLVERS_TIME_SCHEME_H
#define PERISISSM_SOLVERS_TIME_SCHEME_H

#include "solvers/system.h"

namespace PeriSISSM {

class TimeScheme {
 public:
  virtual ~TimeScheme() = default;
  // the time step h
  virtual void set_step(double h) = 0;
  // Start of a step for the unknown rows: keep y^n and v^n as the scheme needs them, the
  // predictor yhat, and the first iterate in y. flag (may be null): a force density taken from
  // the previous step (lagged) that the predictor carries.
  virtual void begin(const Rows &rows, double **y, double **v, double **flag, double **yn,
                     double **yhat) = 0;
  // the factor of the force Jacobian in -dr/dy (h^2 for backward Euler): J = rho I - factor
  // df/dy
  virtual double force_factor() const = 0;
  // residual of one row from its force density f at the current iterate y
  virtual void residual(double rho, const double *yhat, const double *y, const double *f,
                        double *r) const = 0;
  // diagonal block of the residual's Jacobian -dr/dy of one row from the force model's
  // stiffness block K (xx yy zz xy xz yz)
  virtual void block(double rho, const double *K, double D[6]) const = 0;
  // velocities of the unknown rows at the end of a step
  virtual void finish(const Rows &rows, double **y, double **yn, double **v) const = 0;
};

}  // namespace PeriSISSM

#endif  // PERISISSM_SOLVERS_TIME_SCHEME_H
