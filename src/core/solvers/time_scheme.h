// The time scheme of an implicit step (doc/theory.rst, "The implicit step" and "Time schemes"):
// what the unknowns start from, the residual whose root the solvers find, the diagonal blocks
// of its Jacobian, and the velocities at the end. Every scheme solves the same kind of problem
//   r_i(y) = rho_i (yhat_i - y_i) + c f_i(y) = 0
// with its own predictor yhat and force factor c (h^2 for backward Euler, (2h/3)^2 for BDF2 at
// a constant step, beta h^2 (1 - alpha_f) / (1 - alpha_m) for generalized-alpha, whose unknowns
// are the positions at t^{n+1-alpha_f}), so the solvers (jacobi.h, newton_krylov.h), the
// preconditioners and the momentum balance do not know which scheme they solve. One force
// evaluation per residual.
//
// History: a scheme may keep history_columns() doubles per row between steps (BDF2: the last
// step's changes of position and velocity and its acceleration; generalized-alpha: the
// acceleration). The caller owns them (they travel with the atoms), keeps them between steps,
// and sets a row's last column to 0 where it has none (a new row): begin() then starts that row
// from the force density at y^n (fstart), as after a restart. A small global state (the last
// step length) goes with them (state()).

#ifndef PERISISSM_SOLVERS_TIME_SCHEME_H
#define PERISISSM_SOLVERS_TIME_SCHEME_H

#include "solvers/system.h"

#include <memory>
#include <string>

namespace PeriSISSM {

// The per-row arrays of one step (row i of rows.n), owned by the caller.
struct StepArrays {
  double **y = nullptr;         // positions: y^n on begin(), the iterate, then the result
  double **v = nullptr;         // velocities: v^n on begin(), v^{n+1} after finish()
  double **yn = nullptr;        // y^n (written by begin())
  double **vn = nullptr;        // v^n (written by begin(); schemes with history only)
  double **yhat = nullptr;      // the predictor (written by begin())
  double **hist = nullptr;      // history_columns() per row, kept by the caller between steps
  double **flag = nullptr;      // a lagged force density the predictor carries (null: none)
  double **fstart = nullptr;    // force density at y^n (starts rows without history; may be
                                // null for schemes without history)
};

class TimeScheme {
 public:
  virtual ~TimeScheme() = default;
  // the keyword value that selects it (euler, bdf2, genalpha)
  virtual std::string name() const = 0;
  // per-row history columns kept between steps (0: none); the last one is the row's flag
  // (1: its history is valid)
  virtual int history_columns() const { return 0; }
  // the next step has length h
  virtual void set_step(double h) = 0;
  // Start of a step for the unknown rows: y^n and v^n as the scheme needs them, the predictor
  // yhat (with c flag / rho when a lagged force is given), and the first iterate in y (the
  // predictor without the lagged force, plus what the scheme extrapolates from its history: a
  // body at rest in equilibrium is a fixed point for any iteration count).
  virtual void begin(const Rows &rows, const StepArrays &a) = 0;
  // whether begin() may extrapolate the first iterate from the history (on by default; set
  // after each step, off after a step that did not converge: its accelerations are not the scheme's, and on the
  // hanging cloth at 2 ms the fixed 10 sweeps of solver jacobi diverge after about 50 steps when
  // generalized-alpha extrapolates them)
  void set_extrapolation(bool on) { extrapolate_ = on; }
  // the factor c of the force in the residual: J = -dr/dy = rho I - c df/dy
  double force_factor() const { return c_; }
  // where in the step the forces are evaluated, as a fraction of h (1: at t^{n+1}); particles
  // outside the group are placed there while the step is solved
  virtual double force_time() const { return 1.0; }
  // on: evaluate the forces at t^{n+1} (force_time() 1), for a contact that checks the moves of
  // the unknowns, which must then be the step's end positions; a scheme that evaluates them
  // inside the step switches to a member of its family that does not (generalized-alpha:
  // alpha_f = 0); the others have nothing to change
  virtual void set_forces_at_end(bool /*on*/) {}
  // on: keyword error can end the steps (newton_krylov.h), so that a solve ends at an estimate
  // of its error instead of a tolerance; generalized-alpha then guesses the first iterate's
  // acceleration otherwise (generalized_alpha.h), the others have nothing to change
  virtual void set_error_rule(bool /*on*/) {}
  // residual of one row from its force density f at the current iterate y
  void residual(double rho, const double *yhat, const double *y, const double *f, double *r) const
  {
    for (int k = 0; k < 3; k++) r[k] = rho * (yhat[k] - y[k]) + c_ * f[k];
  }
  // residual() of every row of the group (rho: rows.density); the first row whose |r|^2 is not
  // finite (the rest are then not computed), -1 when there is none
  int residuals(const Rows &rows, double **yhat, double **y, double **f, double **r) const;
  // diagonal block of -dr/dy of one row from the force model's stiffness block K
  // (xx yy zz xy xz yz)
  void block(double rho, const double *K, double D[6]) const
  {
    for (int k = 0; k < 6; k++) D[k] = (k < 3 ? rho : 0.0) + c_ * K[k];
  }
  // the velocity that goes with the iterate y of row i where the forces are evaluated (for
  // velocity-dependent forces, e.g. fix viscous)
  virtual void iterate_velocity(int i, const StepArrays &a, double *vel) const = 0;
  // End of a step: the positions of the unknown rows at t^{n+1} in y (from the solved
  // unknowns), their velocities in v, the history for the next step.
  virtual void finish(const Rows &rows, const StepArrays &a) = 0;
  // the global state kept with the history (restart files; a step redone as sub-steps)
  virtual int state_size() const { return 0; }
  virtual void get_state(double * /*s*/) const {}
  virtual void set_state(const double * /*s*/) {}

 protected:
  double h_ = 0.0;    // the step
  double c_ = 0.0;    // the force factor
  bool extrapolate_ = true;
};

// A scheme by keyword value: euler, bdf2, genalpha (rho_inf: the spectral radius at infinite
// h omega, 0 to 1). Null for an unknown name.
std::unique_ptr<TimeScheme> make_time_scheme(const std::string &name, double rho_inf = 1.0);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_TIME_SCHEME_H
