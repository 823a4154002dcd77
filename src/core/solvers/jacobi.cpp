// The SISSM sweep and the Jacobi solver (see jacobi.h).

#include "solvers/jacobi.h"

#include "linalg/small_matrix.h"
#include "solvers/chebyshev.h"

namespace PeriSISSM {

void sissm_sweep(NonlinearSystem &sys, bool first, const SweepMemory &memory, double omega)
{
  const bool extrapolate = omega != 1.0;
  const Rows &rows = sys.rows();
  double **x = sys.unknowns();
  double **res = sys.residual();
  const bool relaxed = memory.rprev != nullptr;

  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    const double *r = res[i];
    double D[6];
    sys.block(i, D);
    double d[3];
    solve_spd3(D, r, d);

    double alpha = 1.0;
    if (relaxed && !first) {
      const double *dp = memory.dprev[i], *rp = memory.rprev[i];
      const double dd = dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2];
      if (dd > 0.0) {
        const double dDd = D[0] * dp[0] * dp[0] + D[1] * dp[1] * dp[1] + D[2] * dp[2] * dp[2] +
            2.0 * (D[3] * dp[0] * dp[1] + D[4] * dp[0] * dp[2] + D[5] * dp[1] * dp[2]);
        const double dr =
            -((r[0] - rp[0]) * dp[0] + (r[1] - rp[1]) * dp[1] + (r[2] - rp[2]) * dp[2]);
        if (dr > dDd) alpha = dDd / dr;
      }
    }
    for (int k = 0; k < 3; k++) {
      d[k] *= alpha;
      const double y = x[i][k];
      if (extrapolate) {
        // (the move made: what the secant of the next sweep measures)
        const double yp = memory.yprev[i][k];
        x[i][k] = omega * (y + d[k] - yp) + yp;
        d[k] = x[i][k] - y;
      } else {
        x[i][k] += d[k];
      }
      if (memory.yprev) memory.yprev[i][k] = y;
      if (relaxed) {
        memory.rprev[i][k] = r[k];
        memory.dprev[i][k] = d[k];
      }
    }
  }
  sys.check_finite();
}

SolveResult solve_jacobi(NonlinearSystem &sys, int maxiter, const SweepMemory &memory, double rho)
{
  SolveResult out;
  ChebyshevWeights weights(rho);
  for (int k = 0; k < maxiter; k++) {
    sys.evaluate(true);
    out.measure = scaled_max(sys, sys.residual(), true);
    if (k == 0) out.tolerance = sys.step_tolerance();
    if (sys.stalled()) break;
    sissm_sweep(sys, k == 0, memory, weights.next());
    if (out.measure <= out.tolerance && sys.evaluation_complete()) break;
  }
  return out;
}

}    // namespace PeriSISSM
