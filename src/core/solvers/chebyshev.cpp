// Chebyshev semi-iterative weights (see chebyshev.h).

#include "solvers/chebyshev.h"

namespace PeriSISSM {

double ChebyshevWeights::next()
{
  given_++;
  if (given_ == 2)
    omega_ = 2.0 / (2.0 - rho2_);
  else if (given_ > 2)
    omega_ = 4.0 / (4.0 - rho2_ * omega_);
  return omega_;
}

}    // namespace PeriSISSM
