// What a step that misses its tolerance does (doc/fix_sissm.rst, keyword unconverged): the
// retry ladder of an implicit step. In order, each rung only while the step has not converged
// and the tolerance is not 0 (tolerance 0 asks for every step to use all its iterations: such a
// step is neither redone nor refused):
//   1. the step, with the preconditioner that converged the last step;
//   2. once more from the start of the step when the preconditioner was built in an earlier
//      step and can be rebuilt now (Preconditioner::refresh());
//   3. with two preconditioners (precond amg and its fallback, the blocks), once more from the
//      start with the other one (measured: a free, rotating soft block at 100 x the explicit
//      limit, where the AMG-preconditioned Newton steps diverge after some steps and the
//      blocks converge);
//   4. unconverged cutback [N]: from the start as 2, 4, ... 2^N equal sub-steps, the first
//      level whose sub-steps all converge ends the step; when none does, the step fails.
// A solve that ends beyond the reach of its contact candidates (StepAttempts::beyond_reach())
// has not converged, whatever its measure; when the whole step does, rungs 2 and 3 are skipped
// (the same step with another preconditioner moves the atoms as far, while shorter sub-steps,
// each starting from fresh candidates, move them less).
// Then the verdict of the step (step_verdict): converged, or with unconverged warn a warning
// (once per run) and the step kept, with unconverged error an error.

#ifndef PERISISSM_SOLVERS_STEP_RETRY_H
#define PERISISSM_SOLVERS_STEP_RETRY_H

#include "solvers/jacobi.h"

namespace PeriSISSM {

enum class Unconverged { warn, error, cutback };

// precond amg: after the blocks converged a step that multigrid did not, they go first for this
// many steps, then multigrid again (measured on examples/twisting-cloth with scheme genalpha,
// 200 steps of 1 ms: one step at 119 that multigrid did not converge; with the blocks first
// for the rest of the run 50.5 evaluations per step, with 10 steps 33.2), or at once when a
// step they went first in needs the ladder's other rungs (the cloth on a ball with 3 layers,
// genalpha, 33 steps of 1 ms: after step 25 the blocks went first in six steps that each failed
// in 100 evaluations and were cut back)
constexpr int kBlocksFirstSteps = 10;

struct RetryPolicy {
  Unconverged unconverged = Unconverged::cutback;
  int max_cutback = 4;         // cutback: at most 2^max_cutback sub-steps
  bool fixed_count = false;    // tolerance 0: no retries, no verdict against the step
  bool two_preconditioners = false;
};

// The step as the ladder drives it (implemented by the integrator).
class StepAttempts {
 public:
  // sub-step s (0 .. n-1) of n equal sub-steps of the step, from where the last one ended
  // (n = 1: the whole step); evaluations() counts the force evaluations it took
  virtual SolveResult solve(int n, int s) = 0;
  virtual int evaluations() const = 0;
  // back to the start of the step (positions, velocities, the time scheme's history)
  virtual void restore_start() = 0;
  // rebuild the preconditioner now; false when it has nothing to rebuild
  virtual bool refresh_preconditioner() = 0;
  // use the other preconditioner from now on
  virtual void switch_preconditioner() = 0;
  // after the sub-steps: the atoms outside the group and the step length as at the step's end
  virtual void end_cutback() = 0;
  // true when the last solve ended with the atoms farther from the last neighbor list build
  // than the contact candidates can follow (asked after every solve unless the count is fixed)
  virtual bool beyond_reach() = 0;

 protected:
  ~StepAttempts() = default;
};

struct RetryOutcome {
  SolveResult result;               // of the last solve
  int evaluations = 0;              // over all attempts
  int substeps = 1;                 // sub-steps of the last level tried (1: not cut back)
  bool refreshed = false;           // rung 2 was taken
  bool switched = false;            // rung 3 was taken
  bool switch_converged = false;    // ... and converged the step
  bool beyond_reach = false;        // the last solve ended beyond the candidates' reach
  bool reach_first = false;         // ... and so did the whole step's first solve
  bool cut_back = false;            // rung 4 was taken
  bool cutback_failed = false;      // ... and no level converged: the step fails
};

RetryOutcome run_retry_ladder(StepAttempts &step, const RetryPolicy &policy);

enum class StepVerdict { converged, warn, error };

// whether the step converged (SolveResult::converged of its last solve)
StepVerdict step_verdict(const RetryPolicy &policy, bool converged);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_STEP_RETRY_H
