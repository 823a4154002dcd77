// The nonlinear system an implicit step solves, as the solvers see it (doc/theory.rst, "The
// implicit step"): unknowns y (one 3-vector per row, the rows of a set of particles), a residual
// r(y) that one evaluation gives (one force evaluation), the diagonal 3x3 blocks of the Jacobian
// J = -dr/dy, and the inner product in which J is symmetric. The time scheme (which residual)
// and the force model (which forces) live behind it; the solvers (jacobi.h, newton_krylov.h) and
// the preconditioner (preconditioner.h) only use this interface.

#ifndef PERISISSM_SOLVERS_SYSTEM_H
#define PERISISSM_SOLVERS_SYSTEM_H

#include "linalg/reductions.h"

namespace PeriSISSM {

// The rows: per-particle 3-vectors as double ** (row i of n local rows); row i is an unknown
// when mask[i] & bit. volume and density weight the inner products and scale the measures.
struct Rows {
  int n = 0;
  const int *mask = nullptr;
  int bit = 0;
  const double *volume = nullptr;
  const double *density = nullptr;
  // V^(1/3) of each row, the particle's size (null: scaled_max computes it from volume)
  const double *size = nullptr;
  bool has(int i) const { return (mask[i] & bit) != 0; }
};

class NonlinearSystem {
 public:
  virtual const Rows &rows() const = 0;
  virtual Reductions &reductions() = 0;
  // the unknowns y (read and written by the solver)
  virtual double **unknowns() = 0;
  // one evaluation of the residual at the current unknowns, into residual(); blocks: also the
  // diagonal blocks for block()
  virtual void evaluate(bool blocks) = 0;
  virtual double **residual() = 0;
  // evaluations since the step began
  virtual int evaluations() const = 0;
  // false when the last evaluation cannot count as converged, whatever its residual (e.g. its
  // contact candidates were incomplete)
  virtual bool evaluation_complete() const = 0;
  // true when the last evaluation's move could not be made and no later one of this solve can
  // (e.g. the reach of the contact candidates from the last neighbor list build, used up: an
  // iterate cut to almost nothing, a Jacobian product's probe cut at all); the solve then ends
  // unconverged at once, leaving the step to its retries (step_retry.h) instead of spending its
  // budget where it stands
  virtual bool stalled() const = 0;
  // diagonal block of row i of J (xx yy zz xy xz yz) from the last evaluation with blocks
  virtual void block(int i, double D[6]) const = 0;
  // the tolerance of this step, asked once after its first evaluation
  virtual double step_tolerance() = 0;
  // the unknowns at the start of the step (y^n), for the step's motion
  virtual double **start() = 0;
  // stop with an error when an unknown is not finite
  virtual void check_finite() = 0;

 protected:
  // not deleted through this interface (its implementations are LAMMPS styles whose
  // destructors may throw)
  ~NonlinearSystem() = default;
};

// sum_i V_i a_i . b_i over the unknown rows (all processes, exact sum; term: n scratch doubles):
// the inner product in which V J = rho V I + h^2 d2E/dy2 is symmetric
double dot(NonlinearSystem &sys, double **a, double **b, double *term);
// sum_i V_i |r_i|^2 / rho_i of the last residual (all processes, exact sum)
double merit(NonlinearSystem &sys, double *term);
// max_i |a_i| / V_i^(1/3) over the unknown rows (all processes), times 1/rho_i when
// per_density: with a = r the convergence measure (the residual as a length relative to the
// particle size; near a stable state J >= rho, so |r|/rho bounds the distance to the solution).
// A row that is not a number makes it infinite (so does it scaled_distance): no tolerance is
// met on it.
double scaled_max(NonlinearSystem &sys, double **a, bool per_density);

// max_i |a_i - b_i| / V_i^(1/3) over the unknown rows (all processes)
double scaled_distance(NonlinearSystem &sys, double **a, double **b);

// the first row of the group whose y_x + y_y + y_z is not finite, -1 when there is none
int first_nonfinite(const Rows &rows, double **y);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_SYSTEM_H
