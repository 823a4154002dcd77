// When precond amg sets its multigrid hierarchy up again (see amg_schedule.h).

#include "solvers/amg_schedule.h"

#include <algorithm>

namespace PeriSISSM {

void AmgSchedule::made_hierarchy()
{
  patterns_++;
  reinterp_ = false;
  fresh_interp_ = true;
}

bool AmgSchedule::setup_wanted(bool same_pattern, double c)
{
  used_ = true;
  return !(same_pattern && !stale_ && set_factor_ == c);
}

bool AmgSchedule::begin_setup(bool same_pattern, bool moved, double c)
{
  fresh_ = true;
  stale_ = false;
  solves_ = 0;
  setups_++;
  set_factor_ = c;
  return same_pattern && (reinterp_ || moved);
}

void AmgSchedule::measured_setup(double applications, bool values_only)
{
  if (values_only || !value_cost_measured_) value_cost_ = applications;
  value_cost_measured_ = value_cost_measured_ || values_only;
}

void AmgSchedule::finished(int newton, int krylov, bool converged)
{
  lagged_ = used_ && !(fresh_ && fresh_interp_);
  if (used_) {
    const double rate = (double) krylov / (newton > 0 ? newton : 1);
    if (solves_++ == 0) {
      baseline_ = rate;
      excess_ = 0.0;
      if (fresh_interp_) interp_baseline_ = rate;
    } else if (rate > 1.5 * interp_baseline_ + 2.0) {
      // (an interpolation that has grown this much worse was made for another configuration)
      stale_ = reinterp_ = true;
    } else {
      // the iterations the lagging values have cost so far, against what new ones cost
      excess_ += std::max(0.0, krylov - baseline_ * newton);
      if (excess_ > value_cost_) stale_ = true;
    }
    if (!converged) stale_ = true;
  }
  used_ = fresh_ = fresh_interp_ = false;
}

// (a solve that never reached a Newton step did not use the hierarchy: nothing to refresh)
bool AmgSchedule::refresh()
{
  stale_ = true;
  reinterp_ = true;
  return lagged_;
}

std::string AmgSchedule::summary() const
{
  return std::to_string(setups_) + " set-up" + (setups_ == 1 ? "" : "s") +
      " of the AMG hierarchy (" + std::to_string(patterns_) +
      " with new aggregates and interpolation)";
}

}    // namespace PeriSISSM
