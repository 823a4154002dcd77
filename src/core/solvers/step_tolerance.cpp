// The tolerance a step can meet (step_tolerance.h).

#include "solvers/step_tolerance.h"

#include <cfloat>
#include <cmath>

namespace PeriSISSM {

namespace {
  double largest_coordinate(const double x[3])
  {
    return fmax(fabs(x[0]), fmax(fabs(x[1]), fabs(x[2])));
  }
}    // namespace

double roundoff_term(const double x[3], const double block[6], double size, double density,
                     double force_factor)
{
  const double bmax = fmax(block[0], fmax(block[1], block[2]));
  return largest_coordinate(x) / size * (1.0 + force_factor * bmax / density);
}

StepTolerance step_tolerance(double asked, const Rows &rows, double **x, double **block,
                             double force_factor, Reductions &reductions)
{
  double largest[2] = {0.0, 0.0};    // the largest term, the largest coordinate
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    largest[0] = fmax(largest[0],
                      roundoff_term(x[i], block[i], rows.size[i], rows.density[i], force_factor));
    largest[1] = fmax(largest[1], largest_coordinate(x[i]));
  }
  reductions.max(largest, 2);
  StepTolerance result;
  result.floor = (asked > 0.0) ? 0.5 * DBL_EPSILON * largest[0] : 0.0;
  result.tolerance = fmax(asked, result.floor);
  result.reach = largest[1];
  return result;
}

}    // namespace PeriSISSM
