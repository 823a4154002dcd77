// Backward Euler (see backward_euler.h).

#include "solvers/backward_euler.h"

namespace PeriSISSM {

void BackwardEuler::begin(const Rows &rows, double **y, double **v, double **flag,
                          double **yn, double **yhat)
{
  const double h = h_, h2 = h2_;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int k = 0; k < 3; k++) {
      yn[i][k] = y[i][k];
      yhat[i][k] = y[i][k] + h * v[i][k];
      if (flag) yhat[i][k] += h2 * flag[i][k] / rows.density[i];
      y[i][k] += h * v[i][k];
    }
  }
}

void BackwardEuler::finish(const Rows &rows, double **y, double **yn, double **v) const
{
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int d = 0; d < 3; d++) v[i][d] = (y[i][d] - yn[i][d]) / h_;
  }
}

}  // namespace PeriSISSM
