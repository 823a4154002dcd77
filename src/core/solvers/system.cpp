// Inner products and measures of the particle systems (see system.h).

#include "solvers/system.h"

#include "linalg/exact_sum.h"

#include <cmath>

namespace PeriSISSM {

namespace {

  // the particle size V_i^(1/3) of row i (rows.size where it is set)
  inline double row_length(const Rows &rows, int i)
  {
    return rows.size ? rows.size[i] : cbrt(rows.volume[i]);
  }

}    // namespace

double dot(NonlinearSystem &sys, double **a, double **b, double *term)
{
  const Rows &rows = sys.rows();
  for (int i = 0; i < rows.n; i++)
    term[i] = rows.has(i)
        ? rows.volume[i] * (a[i][0] * b[i][0] + a[i][1] * b[i][1] + a[i][2] * b[i][2])
        : 0.0;
  return exact_sum(term, rows.n, sys.reductions());
}

double merit(NonlinearSystem &sys, double *term)
{
  const Rows &rows = sys.rows();
  double **res = sys.residual();
  for (int i = 0; i < rows.n; i++)
    term[i] = rows.has(i) ? rows.volume[i] / rows.density[i] *
            (res[i][0] * res[i][0] + res[i][1] * res[i][1] + res[i][2] * res[i][2])
                          : 0.0;
  return exact_sum(term, rows.n, sys.reductions());
}

double scaled_max(NonlinearSystem &sys, double **a, bool per_density)
{
  const Rows &rows = sys.rows();
  double local = 0.0;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    const double length = row_length(rows, i);
    const double size = per_density ? rows.density[i] * length : length;
    const double m = sqrt(a[i][0] * a[i][0] + a[i][1] * a[i][1] + a[i][2] * a[i][2]) / size;
    // (a value that is not a number counts as infinite: no test passes on it)
    if (!(m <= local)) local = std::isnan(m) ? INFINITY : m;
  }
  sys.reductions().max(&local, 1);
  return local;
}

double scaled_distance(NonlinearSystem &sys, double **a, double **b)
{
  const Rows &rows = sys.rows();
  double local = 0.0;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    const double length = row_length(rows, i);
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) d2 += (a[i][k] - b[i][k]) * (a[i][k] - b[i][k]);
    const double m = sqrt(d2) / length;
    if (!(m <= local)) local = std::isnan(m) ? INFINITY : m;
  }
  sys.reductions().max(&local, 1);
  return local;
}

int first_nonfinite(const Rows &rows, double **y)
{
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i) && !std::isfinite(y[i][0] + y[i][1] + y[i][2])) return i;
  return -1;
}

}    // namespace PeriSISSM
