// The retry ladder of an implicit step (step_retry.h).

#include "solvers/step_retry.h"

namespace PeriSISSM {

namespace {

  // whether the last solve settles its (sub-)step: converged, and (unless the count is fixed)
  // ended within the contact candidates' reach, which every solve is asked
  bool settled(StepAttempts &step, const RetryPolicy &policy, RetryOutcome &out)
  {
    out.beyond_reach = !policy.fixed_count && step.beyond_reach();
    return out.result.converged() && !out.beyond_reach;
  }

  // rung 4: levels of 2^level sub-steps; true when a level converged
  bool cut_back(StepAttempts &step, const RetryPolicy &policy, RetryOutcome &out)
  {
    bool done = false;
    for (int level = 1; level <= policy.max_cutback && !done; level++) {
      const int n = 1 << level;
      step.restore_start();
      done = true;
      for (int s = 0; s < n; s++) {
        out.result = step.solve(n, s);
        out.evaluations += step.evaluations();
        if (!settled(step, policy, out)) {
          done = false;
          break;
        }
      }
      out.substeps = n;
    }
    step.end_cutback();
    return done;
  }

}    // namespace

RetryOutcome run_retry_ladder(StepAttempts &step, const RetryPolicy &policy)
{
  RetryOutcome out;
  out.result = step.solve(1, 0);
  out.evaluations = step.evaluations();
  const bool retry = !policy.fixed_count;
  bool done = settled(step, policy, out);
  out.reach_first = out.beyond_reach;
  // (beyond reach, the whole step again moves the atoms as far: straight to the sub-steps)
  if (!done && retry && !out.beyond_reach && step.refresh_preconditioner()) {
    out.refreshed = true;
    step.restore_start();
    out.result = step.solve(1, 0);
    out.evaluations += step.evaluations();
    done = settled(step, policy, out);
  }
  if (!done && retry && !out.beyond_reach && policy.two_preconditioners) {
    out.switched = true;
    step.restore_start();
    step.switch_preconditioner();
    out.result = step.solve(1, 0);
    out.evaluations += step.evaluations();
    done = settled(step, policy, out);
    out.switch_converged = done;
  }
  if (!done && retry && policy.unconverged == Unconverged::cutback) {
    out.cut_back = true;
    out.cutback_failed = !cut_back(step, policy, out);
  }
  return out;
}

StepVerdict step_verdict(const RetryPolicy &policy, bool converged)
{
  if (converged) return StepVerdict::converged;
  if (policy.unconverged == Unconverged::error && !policy.fixed_count) return StepVerdict::error;
  return StepVerdict::warn;
}

}    // namespace PeriSISSM
