// When precond amg sets its multigrid hierarchy up again (see amg_schedule.h).

#include "solvers/amg_schedule.h"

namespace PeriSISSM {

void AmgSchedule::made_hierarchy(long long built)
{
  patterns_++;
  interp_at_ = built;
  reinterp_ = false;
  fresh_interp_ = true;
}

bool AmgSchedule::setup_wanted(bool same_pattern, double c)
{
  used_ = true;
  return !(same_pattern && !stale_ && set_factor_ == c);
}

bool AmgSchedule::begin_setup(bool same_pattern, long long built, double c)
{
  fresh_ = true;
  stale_ = false;
  solves_ = 0;
  setups_++;
  set_factor_ = c;
  return same_pattern && (reinterp_ || interp_at_ != built);
}

void AmgSchedule::finished(int newton, int krylov, bool converged)
{
  lagged_ = used_ && !(fresh_ && fresh_interp_);
  if (used_) {
    const double rate = (double) krylov / (newton > 0 ? newton : 1);
    // (a hierarchy that has grown this much worse was made for another configuration: its
    // interpolation too)
    if (solves_++ == 0)
      baseline_ = rate;
    else if (rate > 1.5 * baseline_ + 2.0)
      stale_ = reinterp_ = true;
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
