// The start of an implicit step (see step_start.h).

#include "solvers/step_start.h"

namespace PeriSISSM {

void keep_start(int n, double **x, double **v, double **hist, const StepStart &start)
{
  for (int i = 0; i < n; i++) {
    for (int k = 0; k < 3; k++) {
      start.x[i][k] = x[i][k];
      start.v[i][k] = v[i][k];
    }
    for (int k = 0; k < start.ncols; k++) start.hist[i][k] = hist[i][k];
  }
}

void keep_start_force(const Rows &rows, double **f, double **fstart, double **hist, int ncols)
{
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i))
      for (int k = 0; k < 3; k++) fstart[i][k] = f[i][k];
    else
      hist[i][ncols - 1] = 0.0;
}

void restore_start(const Rows &rows, const StepStart &start, double **x, double **v, double **hist)
{
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i)) {
      for (int k = 0; k < 3; k++) {
        x[i][k] = start.x[i][k];
        v[i][k] = start.v[i][k];
      }
      for (int k = 0; k < start.ncols; k++) hist[i][k] = start.hist[i][k];
    }
}

void place_others(const Rows &rows, const StepStart &start, double **v, double dt, double t,
                  double **x)
{
  for (int i = 0; i < rows.n; i++)
    if (!rows.has(i))
      for (int k = 0; k < 3; k++) x[i][k] = start.x[i][k] - (1.0 - t) * dt * v[i][k];
}

}    // namespace PeriSISSM
