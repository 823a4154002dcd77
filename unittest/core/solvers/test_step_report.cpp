// What an implicit integrator tells the log about its steps (solvers/step_report.h): each text
// with the numbers of a step, as the log shows them.

#include "solvers/step_report.h"

#include <gtest/gtest.h>

namespace {

using namespace PeriSISSM;

const StepContext kStep{"int", 120, 50, 1.0e-3};

TEST(StepReport, SwitchOfPreconditionerNamesBoth)
{
  RetryOutcome o;
  o.switched = true;
  o.switch_converged = true;
  const RetryTexts t = retry_texts(o, kStep, true);
  EXPECT_EQ(t.warning,
            "Fix sissm int: step 120 did not converge with precond amg; redone with the block "
            "preconditioner (converged; the blocks go first for the next 10 steps; counted "
            "in f_int[9]; reported once per run)");
  EXPECT_EQ(t.error, "");
  EXPECT_EQ(t.note, "");
  EXPECT_NE(
      retry_texts(o, kStep, false).warning.find("(converged; multigrid goes first from now on;"),
      std::string::npos);
  o.switch_converged = false;
  const std::string back = retry_texts(o, kStep, false).warning;
  EXPECT_NE(back.find("with precond block; redone with the amg preconditioner (not converged "
                      "either;"),
            std::string::npos);
}

TEST(StepReport, CutbackNotesTheSubsteps)
{
  RetryOutcome o;
  o.cut_back = true;
  o.substeps = 8;
  const RetryTexts t = retry_texts(o, kStep, false);
  EXPECT_EQ(t.warning, "");
  EXPECT_EQ(t.error, "");
  EXPECT_EQ(t.note,
            "Fix sissm int: step 120 did not converge in 50 iterations; redone as 8 sub-steps of "
            "0.000125 (counted in f_int[6])\n");
  // a step whose first solve went beyond the contact candidates' reach says so
  o.reach_first = true;
  EXPECT_EQ(retry_texts(o, kStep, false).note,
            "Fix sissm int: step 120 went beyond the reach of the contact candidates of the last "
            "neighbor list build; redone as 8 sub-steps of 0.000125 (counted in f_int[6])\n");
}

TEST(StepReport, FailedCutbackIsAnError)
{
  RetryOutcome o;
  o.cut_back = o.cutback_failed = true;
  o.substeps = 16;
  o.result.measure = 3.14159e-4;
  o.result.tolerance = 1.0e-6;
  const RetryTexts t = retry_texts(o, {"int", 7, 100, 0.1}, false);
  EXPECT_EQ(t.note, "");
  EXPECT_EQ(t.error,
            "Fix sissm int: step 7 did not converge in 100 iterations per step, not even as 16 "
            "sub-steps of 0.00625 (convergence measure 0.000314 > tolerance 1e-06): raise "
            "iterations, lower the time step, or accept unconverged steps with 'unconverged "
            "warn'");
}

TEST(StepReport, UnconvergedStepTexts)
{
  EXPECT_EQ(unconverged_cause(2.5e-5, 1.0e-6),
            "this step stopped at the iteration limit with convergence measure 2.5e-05 above "
            "the tolerance 1e-06, so the motion may be an artefact of the unconverged solve");
  EXPECT_EQ(unconverged_error(kStep, 50, 2.5e-5, 2.0e-6),
            "Fix sissm int: step 120 stopped at 50 iterations with convergence measure 2.5e-05 "
            "> tolerance 2e-06 (unconverged error)");
  EXPECT_EQ(unconverged_warning(kStep, 49, 123456.0, 1.0e-6),
            "Fix sissm: step 120 stopped at 49 iterations with convergence measure 1.23e+05 > "
            "tolerance 1e-06 (counted in f_int[4]; reported once per run)");
}

TEST(StepReport, RoundoffFloor)
{
  EXPECT_EQ(roundoff_warning(3, 1.0e4, 2.2e-9, 1.0e-10),
            "Fix sissm: at step 3 round-off in the atom coordinates (up to 1e+04 from the "
            "origin) limits the convergence measure to about 2.2e-09, above the tolerance 1e-10: "
            "steps that reach it count as converged (a body nearer the origin, or a smaller time "
            "step, allows a tighter tolerance; reported once per run)");
}

TEST(StepReport, StatisticsOfARun)
{
  StepStatistics st;
  EXPECT_EQ(st.output(2), 0.0);    // no steps yet
  EXPECT_EQ(st.output(4), 1.0);
  st.begin_step();
  SolveResult r;
  r.newton = 2;
  r.krylov = 11;
  st.solved(r);
  st.solved(r);    // a step redone: both solves count
  st.end_step(30, 2e-7, 1, true, -1.0);
  st.begin_step();
  st.solved(r);
  st.end_step(4, 3e-5, 4, false, -1.0);
  st.cutback++;
  st.switches += 2;
  const double expected[9] = {4, 3e-5, 17, 1, 4, 1, 11, 2, 2};
  for (int n = 0; n < 9; n++) EXPECT_EQ(st.output(n), expected[n]) << n;
  const double expected_error[2] = {0.0, 0.0};
  for (int n = 9; n < 11; n++) EXPECT_EQ(st.output(n), expected_error[n - 9]) << n;
  st.begin_step();
  st.end_step(6, 0.0, 1, true, -1.0);
  EXPECT_EQ(st.output(6), 0.0);    // begin_step cleared the last step's counts
  EXPECT_EQ(st.summary("int"),
            "Fix sissm int run: 3 steps, 13.3333 iterations per step, 1 unconverged, 1 cut back, "
            "2 preconditioner switches");
  // a step that keyword error ended (its measure above the tolerance)
  st.begin_step();
  st.end_step(8, 0.02, 1, true, 0.004);
  EXPECT_EQ(st.output(9), 0.004);
  EXPECT_EQ(st.output(10), 1.0);
  EXPECT_EQ(st.output(3), 1.0);    // not counted as unconverged
  EXPECT_EQ(st.summary("int"),
            "Fix sissm int run: 4 steps, 12 iterations per step, 1 unconverged, 1 cut back, "
            "2 preconditioner switches, 1 ended by the error estimate");
}

}    // namespace
