// Order-independent sums (see exact_sum.h).

#include "linalg/exact_sum.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

namespace PeriSISSM {

void exact_sums(const double *t, int n, int stride, int ncol, Reductions &red, double *out)
{
  std::vector<double> big(ncol, 0.0);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < ncol; k++) big[k] = std::max(big[k], std::fabs(t[i * stride + k]));
  red.max(big.data(), ncol);
  int ecount;
  frexp(red.total_rows(), &ecount);    // rows < 2^ecount
  std::vector<int> q(ncol, 0);
  for (int k = 0; k < ncol; k++) {
    if (!(big[k] > 0.0)) continue;
    int ebig;
    frexp(big[k], &ebig);    // big < 2^ebig
    q[k] = 61 - ebig - ecount;
  }
  // t 2^q: a product with an exact power of two is ldexp's correctly rounded result (2^q a
  // normal double; ldexp itself beyond that range)
  std::vector<double> scale(ncol, 0.0);
  for (int k = 0; k < ncol; k++)
    if (big[k] > 0.0 && q[k] >= DBL_MIN_EXP - 1 && q[k] <= DBL_MAX_EXP - 1)
      scale[k] = ldexp(1.0, q[k]);
  std::vector<long long> sum(ncol, 0);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < ncol; k++) {
      if (!(big[k] > 0.0)) continue;
      const double v = t[i * stride + k];
      sum[k] += llrint(scale[k] > 0.0 ? v * scale[k] : ldexp(v, q[k]));
    }
  red.sum(sum.data(), ncol);
  for (int k = 0; k < ncol; k++) out[k] = (big[k] > 0.0) ? ldexp((double) sum[k], -q[k]) : 0.0;
}

double exact_sum(const double *t, int n, Reductions &red)
{
  double sum;
  exact_sums(t, n, 1, 1, red, &sum);
  return sum;
}

}    // namespace PeriSISSM
