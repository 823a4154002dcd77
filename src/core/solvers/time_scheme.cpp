// The time schemes by name (see time_scheme.h).

#include "solvers/time_scheme.h"

#include "solvers/backward_euler.h"
#include "solvers/bdf2.h"
#include "solvers/generalized_alpha.h"

namespace PeriSISSM {

std::unique_ptr<TimeScheme> make_time_scheme(const std::string &name, double rho_inf)
{
  if (name == "euler") return std::make_unique<BackwardEuler>();
  if (name == "bdf2") return std::make_unique<Bdf2>();
  if (name == "genalpha") return std::make_unique<GeneralizedAlpha>(rho_inf);
  return nullptr;
}

}    // namespace PeriSISSM
