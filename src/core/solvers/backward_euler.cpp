// Backward Euler (see backward_euler.h).

#include "solvers/backward_euler.h"

namespace PeriSISSM {

void BackwardEuler::begin(const Rows &rows, const StepArrays &a)
{
  const double h = h_, h2 = c_;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    double *y = a.y[i];
    const double *v = a.v[i];
    for (int k = 0; k < 3; k++) {
      a.yn[i][k] = y[k];
      a.yhat[i][k] = y[k] + h * v[k];
      if (a.flag) a.yhat[i][k] += h2 * a.flag[i][k] / rows.density[i];
      y[k] += h * v[k];
    }
  }
}

void BackwardEuler::finish(const Rows &rows, const StepArrays &a)
{
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int d = 0; d < 3; d++) a.v[i][d] = (a.y[i][d] - a.yn[i][d]) / h_;
  }
}

}    // namespace PeriSISSM
