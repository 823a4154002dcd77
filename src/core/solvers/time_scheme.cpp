// The time schemes by name (see time_scheme.h).

#include "solvers/time_scheme.h"

#include "solvers/backward_euler.h"
#include "solvers/bdf2.h"
#include "solvers/generalized_alpha.h"

#include <cmath>

namespace PeriSISSM {

int TimeScheme::residuals(const Rows &rows, double **yhat, double **y, double **f, double **r) const
{
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    residual(rows.density[i], yhat[i], y[i], f[i], r[i]);
    const double r2 = r[i][0] * r[i][0] + r[i][1] * r[i][1] + r[i][2] * r[i][2];
    if (!std::isfinite(r2)) return i;
  }
  return -1;
}

std::unique_ptr<TimeScheme> make_time_scheme(const std::string &name, double rho_inf)
{
  if (name == "euler") return std::make_unique<BackwardEuler>();
  if (name == "bdf2") return std::make_unique<Bdf2>();
  if (name == "genalpha") return std::make_unique<GeneralizedAlpha>(rho_inf);
  return nullptr;
}

}    // namespace PeriSISSM
