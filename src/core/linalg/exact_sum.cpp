// Order-independent sums (see exact_sum.h).

#include "linalg/exact_sum.h"

#include <cmath>
#include <vector>

namespace PeriSISSM {

void exact_sums(const double *t, int n, int stride, int ncol, Reductions &red, double *out)
{
  std::vector<double> big(ncol, 0.0);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < ncol; k++) big[k] = fmax(big[k], fabs(t[i * stride + k]));
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
  std::vector<long long> sum(ncol, 0);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < ncol; k++)
      if (big[k] > 0.0) sum[k] += llrint(ldexp(t[i * stride + k], q[k]));
  red.sum(sum.data(), ncol);
  for (int k = 0; k < ncol; k++) out[k] = (big[k] > 0.0) ? ldexp((double) sum[k], -q[k]) : 0.0;
}

double exact_sum(const double *t, int n, Reductions &red)
{
  double sum;
  exact_sums(t, n, 1, 1, red, &sum);
  return sum;
}

}  // namespace PeriSISSM
