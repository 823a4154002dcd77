// Stable explicit time step estimate (see stable_step.h).

#include "peri/stable_step.h"

#include "materials/material.h"
#include "peri/model.h"

#include <cmath>
#include <limits>

namespace PeriSISSM {

double stable_step_stiffness(const Material &material, const double Kinv[9], double C,
                             bool membrane)
{
  const double kappa = (Kinv[0] + Kinv[4] + Kinv[8]) / (membrane ? 2.0 : 3.0);
  return kappa * (material.lambda() + 2.0 * material.mu()) + 0.5 * C;
}

double stable_time_step(double rho, double d)
{
  return (d > 0.0) ? kStableStepSafety * std::sqrt(2.0 * rho / d)
                   : std::numeric_limits<double>::infinity();
}

void stable_step_stiffnesses(const Model &model, int n, const int *type, const double *const *kinv,
                             const int *kregular, double *s)
{
  for (int i = 0; i < n; i++)
    s[i] = kregular[i] ? stable_step_stiffness(model.material(type[i]), kinv[i],
                                               model.stabilization_modulus(type[i], kinv[i]),
                                               model.membrane(type[i]))
                       : 0.0;
}

}    // namespace PeriSISSM
