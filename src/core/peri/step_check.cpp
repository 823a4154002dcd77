// The time step check of explicit runs (see step_check.h).

#include "peri/step_check.h"

#include "linalg/general_format.h"

#include <algorithm>
#include <limits>

namespace PeriSISSM {

bool explicit_integrator(const std::string &style)
{
  return style != "sissm" && style != "move" && style != "nve/noforce" &&
      style.compare(0, 5, "rigid") != 0;
}

StepExcess step_excess(int n, const double *dt, const int *mask, int bits, double step)
{
  StepExcess excess = {std::numeric_limits<double>::infinity(), 0, 0};
  for (int i = 0; i < n; i++) {
    if (!(mask[i] & bits)) continue;
    excess.counted++;
    excess.smallest = std::min(excess.smallest, dt[i]);
    if (dt[i] < step) excess.above++;
  }
  return excess;
}

std::string step_warning(double step, double smallest, int64_t above, int64_t total,
                         const std::string &fixes)
{
  return "Pair peri/nosb: timestep " + general_format(step, 4) +
      " is above the estimated stable explicit time step " + general_format(smallest, 4) + " of " +
      std::to_string(above) + " of the " + std::to_string(total) + " particles integrated by fix " +
      fixes +
      ": an explicit run above it can blow up, or break bonds and run on to a wrong answer "
      "without an error. Use a timestep below " +
      general_format(smallest, 4) +
      " or the implicit fix sissm (compute nosb/atom column 11 gives the estimate per particle)";
}

}    // namespace PeriSISSM
