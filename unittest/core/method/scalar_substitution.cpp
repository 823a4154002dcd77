// The method's one-variable successive substitution example.

#include "scalar_substitution.h"

#include <utility>

namespace PeriSISSM {

std::vector<double> iterate(const ScalarMap &g, double x0, int n)
{
  std::vector<double> xs;
  xs.reserve(n > 0 ? n + 1 : 1);
  xs.push_back(x0);
  for (int k = 0; k < n; ++k) xs.push_back(g(xs.back()));
  return xs;
}

// x_{k+1} (1 + a) = g(x_k) + a x_k  (header).
ScalarMap split_map(ScalarMap g, double a)
{
  return [g = std::move(g), a](double x) {
    return (g(x) + a * x) / (1.0 + a);
  };
}

double talk_example_map(double x)
{
  return (x - 2.0) * (x - 2.0);
}

}    // namespace PeriSISSM
