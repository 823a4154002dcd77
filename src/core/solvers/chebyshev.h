// Chebyshev semi-iterative acceleration of a stationary iteration (Wang 2015, "A Chebyshev
// semi-iterative approach for accelerating projective and position-based dynamics"; Golub and
// Van Loan, "Matrix Computations", section 11.2.8): with yhat^{k+1} the plain sweep from y^k,
//   y^{k+1} = omega_{k+1} (yhat^{k+1} - y^{k-1}) + y^{k-1}
//   omega_1 = 1, omega_2 = 2 / (2 - rho^2), omega_{k+1} = 4 / (4 - rho^2 omega_k)
// where rho is the spectral radius of the sweep's iteration matrix (its eigenvalues real, in
// [-rho, rho]). For a linear iteration the error after k sweeps is then the Chebyshev polynomial
// of degree k in the iteration matrix, scaled to 1 at 1: its largest value on [-rho, rho] falls
// as (rho / (1 + sqrt(1 - rho^2)))^k instead of rho^k. The fixed point is the sweep's own. After
// omega_1 = 1 the weights fall from omega_2, the largest, towards 2 / (1 + sqrt(1 - rho^2)) (< 2).

#ifndef PERISISSM_SOLVERS_CHEBYSHEV_H
#define PERISISSM_SOLVERS_CHEBYSHEV_H

namespace PeriSISSM {

class ChebyshevWeights {
 public:
  // rho: the estimated spectral radius of the sweep, 0 <= rho < 1 (0: every weight is 1)
  explicit ChebyshevWeights(double rho) : rho2_(rho * rho) {}
  // the weight of the next sweep: omega_1, omega_2, ... in turn
  double next();

 private:
  double rho2_;
  int given_ = 0;         // weights given so far
  double omega_ = 1.0;    // the last one
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_CHEBYSHEV_H
