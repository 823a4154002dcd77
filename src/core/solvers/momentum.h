// Momentum balance of a free group after an implicit step (doc/theory.rst, "Momentum of
// truncated solves"), for every step, converged or not:
//   P^{n+1} = P^n + h F,        F = sum_i V_i fext_i,
//   L^{n+1} = L^n + h T,        T = sum_i V_i r_i x fext_i,
// P = sum_i m_i v_i, L = sum_i m_i q_i x v_i the angular momentum about the centre of mass
// (q_i = y_i - c), m_i = rho_i V_i, fext the external force density of the last evaluation and
// r_i = y_i^{n+1} - c^{n+1} (a lagged external force is in yhat instead, so that
// m (yhat - y^n) / h = m v^n + h V fext, and its force and torque at y^n are in the targets).
// With v^{n+1} = (y^{n+1} - y^n)/h and sum_i m_i q_i^n = 0,
//   sum_i m_i (y_i^{n+1} - y_i^n) = h P^{n+1},   L^{n+1} = (1/h) sum_i m_i q_i^n x r_i.
// The internal forces of a free group have zero sum and zero torque at any positions (their
// energy is invariant under translation and rotation), so a converged backward-Euler step
// keeps P exactly; a truncated solve does not, and a free body at rest would pick up a rigid
// velocity. Backward Euler itself changes L by h sum_i m_i v_i^{n+1} x v_i^n (it damps
// rotation). The correction moves the result rigidly: its centre by d (from the first
// balance, exactly), and the rest by a rotation R about the centre, r_i -> R r_i, found by
// Newton's method on G(R) = (1/h) sum m q^n x R r - h sum V (R r) x fext - L^n = 0 with
//   dG = J dtheta,  J = (1/h) sum_i m_i ((q_i^n . r_i) I - r_i q_i^nT)
//                        - h sum_i V_i (r_i fext_i^T - (r_i . fext_i) I)
// (rotation increments composed exactly, Rodrigues' formula): a rotation changes no bond
// length, so the deformation and its energy are untouched. A converged step needs a rotation
// of ~1e-4 rad or less, reached to round-off in two iterations; at most 8 are made. All
// terms are relative to the centres (coordinates far from the origin would cost digits), and
// the sums are order-independent, so every process count corrects alike.
//
// Other time schemes (BDF2, generalized-alpha; time_scheme.h) solve rho (y - yhat) = c f(y)
// with their own yhat and c, and their velocities are not (y^{n+1} - y^n)/h. For them the
// balance asks of every step what a converged step of the scheme satisfies for a free group:
//   sum_i m_i (y_i - yhat_i) = c F                                       (linear)
//   G(R) = sum_i (R r_i) x b_i = 0,  b_i = m_i (yhat_i - c^n) + c V_i fext_i   (angular)
// (the internal forces have zero sum and zero torque at y; r_i = y_i - c, c the centre of the
// corrected y; sum_i m_i R r_i = 0, so the centre in b does not matter), with
//   dG = J dtheta,  J = sum_i ((R r_i) b_i^T - ((R r_i) . b_i) I).

#ifndef PERISISSM_SOLVERS_MOMENTUM_H
#define PERISISSM_SOLVERS_MOMENTUM_H

#include "solvers/system.h"

namespace PeriSISSM {

// columns of the work table of balance_momentum()
constexpr int kMomentumColumns = 15;

// which angular balance (see above): backward Euler's L^{n+1} = L^n + h T, or the converged
// step's identity of a scheme with force factor c
struct MomentumBalance {
  double h = 0.0;       // the time step
  double c = 0.0;       // the scheme's force factor (h^2 for backward Euler)
  bool euler = true;    // true: backward Euler's balance; false: the general one
};

// Inputs: the unknown rows (a free group), reductions, the scheme's step (above), y^{n+1} (the
// solved unknowns, corrected in place), y^n, yhat, fext (null when the external force is lagged
// into yhat); moment: work table of rows.n x kMomentumColumns doubles.
void balance_momentum(const Rows &rows, Reductions &red, const MomentumBalance &step, double **y,
                      double **yn, double **yhat, double **fext, double **moment);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_MOMENTUM_H
