// The SISSM sweep and the Jacobi solver (doc/theory.rst, "The SISSM iteration"):
//   y_i <- y_i + alpha_i D_i^-1 r_i(y)
// with D_i the diagonal block of J. relax yes (after the first sweep of a step): a secant
// estimate of the particle's stiffness along its last move Delta: the residual changed by
// -(stiffness) Delta; when the true response is stiffer than D assumed (Delta.D.Delta), the
// move is scaled back by their ratio. chebyshev rho (solve_jacobi's rho > 0): each sweep's result
// is extrapolated by the Chebyshev weights of chebyshev.h, y <- omega (yhat - yprev) + yprev with
// yprev the iterate the last sweep started from; relax then measures its secant along the move
// that was made (the extrapolated one).

#ifndef PERISISSM_SOLVERS_JACOBI_H
#define PERISISSM_SOLVERS_JACOBI_H

#include "solvers/system.h"

namespace PeriSISSM {

// What a solve ended with: the convergence measure of its last evaluation and the tolerance
// the step was held to (the system's step_tolerance()).
struct SolveResult {
  double measure = 0.0;
  double tolerance = 0.0;
  int newton = 0;    // Newton steps (krylov)
  int krylov = 0;    // conjugate-gradient iterations over all Newton steps (krylov)
  // keyword error (newton_krylov.h): the estimated position error over the step's largest
  // motion when that rule ended the solve, 0 otherwise
  double error = 0.0;
  bool error_met = false;
  bool converged() const { return measure <= tolerance || error_met; }
};

// Work rows of the sweeps: those of relax (both null without relax) and of chebyshev (null
// without it).
struct SweepMemory {
  double **rprev = nullptr;    // residual of the previous sweep
  double **dprev = nullptr;    // move of the previous sweep
  double **yprev = nullptr;    // the iterate the previous sweep started from
};

// One sweep from the last evaluation (residual and blocks); first: the first sweep of the step
// (no secant estimate yet, no earlier iterate); omega: its Chebyshev weight (1: the plain sweep;
// otherwise memory.yprev is needed).
void sissm_sweep(NonlinearSystem &sys, bool first, const SweepMemory &memory, double omega = 1.0);

// Up to maxiter sweeps; each evaluates the residual of the iterate it starts from, and the sweep
// whose starting residual meets the tolerance is the last one. rho > 0 (< 1): the sweeps are
// accelerated by the Chebyshev weights of that spectral radius (memory.yprev needed).
SolveResult solve_jacobi(NonlinearSystem &sys, int maxiter, const SweepMemory &memory,
                         double rho = 0.0);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_JACOBI_H
