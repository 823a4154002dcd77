// Inexact Newton on r(y) = 0 with J = -dr/dy (symmetric in the system's inner product), each
// Newton step J s = r(y_base) solved by preconditioned conjugate gradients (doc/theory.rst,
// "Newton-Krylov acceleration"). The first CG direction is the preconditioned residual (with
// the block preconditioner: the SISSM correction D^-1 r). J p = (r(y_base) - r(y_base + e p)) / e,
// e = 1e-7 / max_i |p_i| / l_i: one evaluation per CG iteration. CG stops when its residual
// estimate meets max(tolerance/4, eta * measure) (eta: Eisenstat-Walker), at non-positive
// curvature (then the preconditioned residual is used if CG has no step yet) or at the
// evaluation budget.
// Safeguard: a Newton step s that fails the Armijo condition on the step's incremental
// potential (judged from <s, r> at both ends, trapezoid rule; where s is not a descent
// direction: one that increases phi = sum_i V_i |r_i|^2 / rho_i) is shortened (at most 4
// times). Budget (maxiter evaluations, never more): CG keeps one evaluation to check its
// Newton iterate; when that check finds it worse than its base and no budget is left, the step
// ends at the base plus its SISSM correction D^-1 r; when the budget ends at an accepted
// evaluation, one SISSM sweep uses it, so krylov with iterations 1 equals jacobi with
// iterations 1. The evaluation that meets the tolerance also gives its SISSM correction.

#ifndef PERISISSM_SOLVERS_NEWTON_KRYLOV_H
#define PERISISSM_SOLVERS_NEWTON_KRYLOV_H

#include "solvers/jacobi.h"
#include "solvers/preconditioner.h"

namespace PeriSISSM {

// Work rows (n rows of 3 each, term n doubles), owned by the caller.
struct KrylovWork {
  double **xbase = nullptr, **rbase = nullptr, **jbase = nullptr, **cres = nullptr,
         **zdir = nullptr, **pdir = nullptr, **sdir = nullptr;
  double *term = nullptr;
};

// Newton steps are accepted on the step's incremental potential (Armijo, see
// newton_krylov.cpp), on the residual norm where the step is not a descent direction
SolveResult solve_newton_krylov(NonlinearSystem &sys, Preconditioner &precond, int maxiter,
                                const KrylovWork &work);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_NEWTON_KRYLOV_H
