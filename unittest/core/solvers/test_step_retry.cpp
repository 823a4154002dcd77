// The retry ladder of an implicit step (solvers/step_retry.h) on a scripted step: each solve
// returns the next outcome of a script, and the test checks which rungs were taken, in which
// order, with which sub-steps, and the verdict.

#include "solvers/step_retry.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using namespace PeriSISSM;

// A step whose solves converge or not as scripted ('c' or 'u', one per solve, in order); what
// the ladder asked for is recorded as text: "S1.0" a solve of sub-step 0 of 1, "R" restore,
// "F" refresh asked (answered by refresh_ok), "P" switch, "E" end of cutback.
class ScriptedStep : public StepAttempts {
 public:
  ScriptedStep(std::string script, bool refresh_ok = false) :
      script_(std::move(script)), refresh_ok_(refresh_ok)
  {
  }
  SolveResult solve(int n, int s) override
  {
    log += "S" + std::to_string(n) + "." + std::to_string(s) + " ";
    EXPECT_LT(next_, script_.size()) << "more solves than scripted: " << log;
    // c: converged, u: not, r: not and beyond reach, R: converged measure but beyond reach
    const char c = next_ < script_.size() ? script_[next_] : 'u';
    const bool ok = c == 'c' || c == 'R';
    far_ = c == 'r' || c == 'R';
    next_++;
    SolveResult r;
    r.tolerance = 1e-6;
    r.measure = ok ? 1e-7 : 1e-3;
    return r;
  }
  int evaluations() const override { return 10; }
  void restore_start() override { log += "R "; }
  bool refresh_preconditioner() override
  {
    log += "F ";
    return refresh_ok_;
  }
  void switch_preconditioner() override { log += "P "; }
  void end_cutback() override { log += "E "; }
  bool beyond_reach() override
  {
    reach_asked++;
    return far_;
  }

  std::string log;
  int reach_asked = 0;
  size_t solves() const { return next_; }

 private:
  std::string script_;
  bool refresh_ok_;
  size_t next_ = 0;
  bool far_ = false;
};

RetryPolicy policy(Unconverged u, int levels = 4, bool two = false, bool fixed = false)
{
  RetryPolicy p;
  p.unconverged = u;
  p.max_cutback = levels;
  p.two_preconditioners = two;
  p.fixed_count = fixed;
  return p;
}

// A converged step is solved once, nothing else asked.
TEST(StepRetry, ConvergedStepIsSolvedOnce)
{
  ScriptedStep step("c");
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::cutback, 4, true));
  EXPECT_EQ(step.log, "S1.0 ");
  EXPECT_TRUE(out.result.converged());
  EXPECT_EQ(out.evaluations, 10);
  EXPECT_EQ(out.substeps, 1);
  EXPECT_FALSE(out.refreshed || out.switched || out.cut_back || out.cutback_failed);
}

// warn: an unconverged step asks the preconditioner for a refresh (none here) and is kept.
TEST(StepRetry, WarnKeepsTheUnconvergedStep)
{
  ScriptedStep step("u");
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::warn));
  EXPECT_EQ(step.log, "S1.0 F ");
  EXPECT_FALSE(out.result.converged());
  EXPECT_EQ(step_verdict(policy(Unconverged::warn), out.result.converged()), StepVerdict::warn);
  EXPECT_EQ(step_verdict(policy(Unconverged::error), out.result.converged()), StepVerdict::error);
  EXPECT_EQ(step_verdict(policy(Unconverged::error), true), StepVerdict::converged);
}

// A preconditioner built in an earlier step is rebuilt and the step redone from its start.
TEST(StepRetry, RefreshedPreconditionerRedoesTheStep)
{
  ScriptedStep step("uc", true);
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::error));
  EXPECT_EQ(step.log, "S1.0 F R S1.0 ");
  EXPECT_TRUE(out.refreshed);
  EXPECT_TRUE(out.result.converged());
  EXPECT_EQ(out.evaluations, 20);
}

// Two preconditioners: the other one redoes the step; whether it converged is reported.
TEST(StepRetry, OtherPreconditionerRedoesTheStep)
{
  ScriptedStep good("uc");
  const RetryOutcome a = run_retry_ladder(good, policy(Unconverged::warn, 4, true));
  EXPECT_EQ(good.log, "S1.0 F R P S1.0 ");
  EXPECT_TRUE(a.switched && a.switch_converged && a.result.converged());

  ScriptedStep bad("uu");
  const RetryOutcome b = run_retry_ladder(bad, policy(Unconverged::warn, 4, true));
  EXPECT_EQ(bad.log, "S1.0 F R P S1.0 ");
  EXPECT_TRUE(b.switched);
  EXPECT_FALSE(b.switch_converged || b.cut_back);
}

// cutback: 2 sub-steps, the second unconverged, then 4 that all converge: the step ends as 4.
TEST(StepRetry, CutbackStopsAtTheFirstLevelThatConverges)
{
  ScriptedStep step("ucucccc");
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::cutback, 4));
  EXPECT_EQ(step.log, "S1.0 F R S2.0 S2.1 R S4.0 S4.1 S4.2 S4.3 E ");
  EXPECT_TRUE(out.cut_back);
  EXPECT_FALSE(out.cutback_failed);
  EXPECT_EQ(out.substeps, 4);
  EXPECT_EQ(out.evaluations, 70);
  EXPECT_TRUE(out.result.converged());
}

// cutback N: after 2^N sub-steps that do not all converge, the step fails; a level stops at
// its first unconverged sub-step.
TEST(StepRetry, CutbackFailsAfterItsLastLevel)
{
  ScriptedStep step("ucu");
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::cutback, 1));
  EXPECT_EQ(step.log, "S1.0 F R S2.0 S2.1 E ");
  EXPECT_EQ(step.solves(), 3u);
  EXPECT_TRUE(out.cut_back && out.cutback_failed);
  EXPECT_EQ(out.substeps, 2);
  EXPECT_FALSE(out.result.converged());
}

// The rungs in order: refresh, the other preconditioner, then the sub-steps.
TEST(StepRetry, AllRungsInOrder)
{
  ScriptedStep step("uuucc", true);
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::cutback, 3, true));
  EXPECT_EQ(step.log, "S1.0 F R S1.0 R P S1.0 R S2.0 S2.1 E ");
  EXPECT_TRUE(out.refreshed && out.switched && out.cut_back);
  EXPECT_FALSE(out.switch_converged || out.cutback_failed);
  EXPECT_EQ(out.substeps, 2);
  EXPECT_EQ(out.evaluations, 50);
}

// A solve that ends beyond the contact candidates' reach has not converged, whatever its
// measure; a whole step that does goes straight to the sub-steps: no refresh, no other
// preconditioner (either would move the atoms as far). With warn it is kept (the integrator
// refuses it). Every solve is asked.
TEST(StepRetry, BeyondReachGoesStraightToTheSubsteps)
{
  ScriptedStep step("rcRcccc", true);
  const RetryOutcome out = run_retry_ladder(step, policy(Unconverged::cutback, 4, true));
  EXPECT_EQ(step.log, "S1.0 R S2.0 S2.1 R S4.0 S4.1 S4.2 S4.3 E ");
  EXPECT_TRUE(out.cut_back);
  EXPECT_FALSE(out.beyond_reach || out.refreshed || out.switched || out.cutback_failed);
  EXPECT_TRUE(out.reach_first);    // (the log says why it was cut back)
  EXPECT_EQ(out.substeps, 4);
  EXPECT_EQ(step.reach_asked, 7);

  ScriptedStep kept("R", true);
  const RetryOutcome w = run_retry_ladder(kept, policy(Unconverged::warn, 4, true));
  EXPECT_EQ(kept.log, "S1.0 ");
  EXPECT_TRUE(w.beyond_reach);

  // the last level ends beyond reach: the step fails, and says why
  ScriptedStep far("rr", true);
  const RetryOutcome f = run_retry_ladder(far, policy(Unconverged::cutback, 1, true));
  EXPECT_EQ(far.log, "S1.0 R S2.0 E ");
  EXPECT_TRUE(f.cutback_failed && f.beyond_reach);

  // within reach: the ladder as before
  ScriptedStep near("uuc", true);
  const RetryOutcome n = run_retry_ladder(near, policy(Unconverged::cutback, 4, true));
  EXPECT_EQ(near.log, "S1.0 F R S1.0 R P S1.0 ");
  EXPECT_FALSE(n.beyond_reach || n.reach_first);
  EXPECT_EQ(near.reach_asked, 3);

  // a fixed count is not asked
  ScriptedStep fixed("R", true);
  EXPECT_FALSE(run_retry_ladder(fixed, policy(Unconverged::error, 4, true, true)).beyond_reach);
  EXPECT_EQ(fixed.reach_asked, 0);
}

// Tolerance 0 (fixed_count): one solve, no retry, no error verdict even with unconverged error.
TEST(StepRetry, FixedCountIsNeverRetriedNorRefused)
{
  ScriptedStep step("u", true);
  const RetryPolicy p = policy(Unconverged::error, 4, true, true);
  const RetryOutcome out = run_retry_ladder(step, p);
  EXPECT_EQ(step.log, "S1.0 ");
  EXPECT_EQ(step_verdict(p, out.result.converged()), StepVerdict::warn);
}

}    // namespace
