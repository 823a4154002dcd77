// Inexact Newton on r(y) = 0 with J = -dr/dy (symmetric in the system's inner product), each
// Newton step J s = r(y_base) solved by preconditioned conjugate gradients (doc/theory.rst,
// "Newton-Krylov acceleration"). The first CG direction is the preconditioned residual (with
// the block preconditioner: the SISSM correction D^-1 r). J p = (r(y_base) - r(y_base + e p)) / e,
// e = 1e-7 / max_i |p_i| / l_i: one evaluation per CG iteration. CG stops when its residual
// estimate meets max(tolerance/4, eta * measure) (eta: the forcing term, NewtonForcing below),
// at non-positive curvature (then the preconditioned residual is used if CG has no step yet) or
// at the evaluation budget.
// Safeguard: a Newton step s that fails the Armijo condition on the step's incremental
// potential (judged from <s, r> at both ends, trapezoid rule; where s is not a descent
// direction: one that increases phi = sum_i V_i |r_i|^2 / rho_i) is shortened (at most 4
// times). Budget (maxiter evaluations, never more): CG keeps one evaluation to check its
// Newton iterate; when that check finds it worse than its base and no budget is left, the step
// ends at the base plus its SISSM correction D^-1 r; when the budget ends at an accepted
// evaluation, one SISSM sweep uses it, so krylov with iterations 1 equals jacobi with
// iterations 1. The evaluation that meets the tolerance also gives its SISSM correction.
// Keyword error (error > 0, with a preconditioner whose z = M^-1 r estimates the distance to the
// solution, precond amg): the step has also converged at an evaluation whose estimate
// max_i |z_i| / l_i is at most error times the step's largest motion max_i |y_i - y_i^n| / l_i
// (checked before each Newton step, z being the first CG direction; the evaluated iterate is
// the result, uncorrected: a sweep on a residual that large is not a safe move), and CG stops
// once its own z is a quarter of that target. The residual measure bounds the distance to the
// solution by |r_i| / rho_i, which overstates it by up to (h omega)^2 for the stiff modes that
// a large step takes in one solve (measured on examples/hanging-cloth at 2 ms: the first
// iterate's measure 0.03 to 0.6, its first Newton step 0.006 to 0.01 particle sizes, z within a
// third of that step).

#ifndef PERISISSM_SOLVERS_NEWTON_KRYLOV_H
#define PERISISSM_SOLVERS_NEWTON_KRYLOV_H

#include "solvers/jacobi.h"
#include "solvers/preconditioner.h"

namespace PeriSISSM {

// The forcing term eta (Eisenstat and Walker 1996, "Choosing the forcing terms in an inexact
// Newton method", SIAM J. Sci. Comput. 17). Their choice 1, after a full Newton step: how far
// the linear model missed, |m(new iterate) - m(CG's residual)| / m(base) in the residual
// measure m, kept at least eta_prev^((1 + sqrt 5) / 2) when that exceeds 0.1 (their
// safeguard), within [1e-4, kMaxForcing]. Their choice 2: 0.9 (m / m_prev)^2 within [1e-4,
// 0.1]. A solve that the error estimate can end (keyword error with an estimating
// preconditioner) takes choice 1 from its second Newton step on; one held to the tolerance
// alone takes choice 2, which tightens as the measure falls towards it; after a step that the
// line search shortened, choice 2. A solve's first Newton step has no measure of its own: it
// takes the first choice-1 term of the last solve that computed one, kept in NewtonForcing
// (1e-2 before any), so that where the linear model holds (a hanging cloth) a step's first
// Newton step is solved tightly, and where it does not (a barrier in contact, whose Newton
// steps gain a factor of 2 to 10 each) CG does not solve to 1e-2 a model that the next
// iterate misses by far.
constexpr double kMaxForcing = 0.5;
struct NewtonForcing {
  double first = 1.0e-2;    // the first Newton step's forcing term of the next solve
};

// Work rows (n rows of 3 each, term n doubles), owned by the caller; forcing: carried from
// solve to solve (null: 1e-2 for every solve's first Newton step)
struct KrylovWork {
  double **xbase = nullptr, **rbase = nullptr, **jbase = nullptr, **cres = nullptr,
         **zdir = nullptr, **pdir = nullptr, **sdir = nullptr;
  double *term = nullptr;
  NewtonForcing *forcing = nullptr;
};

// Newton steps are accepted on the step's incremental potential (Armijo, see
// newton_krylov.cpp), on the residual norm where the step is not a descent direction
SolveResult solve_newton_krylov(NonlinearSystem &sys, Preconditioner &precond, int maxiter,
                                const KrylovWork &work, double error = 0.0);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_NEWTON_KRYLOV_H
