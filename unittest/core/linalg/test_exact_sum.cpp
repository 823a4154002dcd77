// Order-independent sums (linalg/exact_sum.h).

#include "linalg/exact_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

// Terms spanning 12 decades with both signs: the sum does not depend on their order (bit for
// bit), and is within N 2^-q / 2 of the exact sum, where every term is rounded to a multiple of
// 2^-q with 2^q T N < 2^61 (T = max|t| < 2^e): N 2^-q / 2 <= N^2 2 T 2^-61 (long double
// reference, 64-bit mantissa, exact enough for N = 5000).
TEST(ExactSum, IndependentOfOrderAndAccurate)
{
  std::mt19937_64 rng(1u);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-12.0, 0.0);
  const int n = 5000;
  std::vector<double> t(n);
  for (double &v : t) v = u(rng) * std::pow(10.0, e(rng));
  PeriSISSM::SerialReductions red(n);
  const double s0 = PeriSISSM::exact_sum(t.data(), n, red);
  long double ref = 0.0L;
  double tmax = 0.0;
  for (double v : t) {
    ref += v;
    tmax = std::max(tmax, std::fabs(v));
  }
  EXPECT_LE(std::fabs((long double) s0 - ref), (double) n * n * 2.0 * tmax * std::ldexp(1.0, -61));
  for (int trial = 0; trial < 5; trial++) {
    std::shuffle(t.begin(), t.end(), rng);
    EXPECT_EQ(PeriSISSM::exact_sum(t.data(), n, red), s0);
  }
}

// Several columns at once give each column's own sum; an all-zero column sums to zero.
TEST(ExactSum, ColumnsAreIndependent)
{
  const int n = 7;
  std::vector<double> t(3 * n);
  for (int i = 0; i < n; i++) {
    t[3 * i] = i + 1;
    t[3 * i + 1] = 0.0;
    t[3 * i + 2] = -0.5 * (i + 1);
  }
  PeriSISSM::SerialReductions red(n);
  double out[3];
  PeriSISSM::exact_sums(t.data(), n, 3, 3, red, out);
  EXPECT_EQ(out[0], 28.0);
  EXPECT_EQ(out[1], 0.0);
  EXPECT_EQ(out[2], -14.0);
}

}    // namespace
