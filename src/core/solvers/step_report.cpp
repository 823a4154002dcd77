// What an implicit integrator tells the log about its steps (see step_report.h).

#include "solvers/step_report.h"

#include "linalg/general_format.h"

namespace PeriSISSM {

namespace {

  std::string n(long long x)
  {
    return std::to_string(x);
  }

}    // namespace

RetryTexts retry_texts(const RetryOutcome &outcome, const StepContext &c, bool now_block)
{
  RetryTexts texts;
  const std::string me = "Fix sissm " + c.id + ": step " + n(c.step) + " did not converge ";
  if (outcome.switched)
    texts.warning = me + "with precond " + (now_block ? "amg" : "block") + "; redone with the " +
        (now_block ? "block" : "amg") + " preconditioner (" +
        (!outcome.switch_converged ? "not converged either"
             : now_block
             ? "converged; the blocks go first for the next " + n(kBlocksFirstSteps) + " steps"
             : "converged; multigrid goes first from now on") +
        "; counted in f_" + c.id + "[9]; reported once per run)";
  if (!outcome.cut_back) return texts;
  const int substeps = outcome.substeps;
  const std::string sub = n(substeps) + " sub-steps of " + general_format(c.dt / substeps, 6);
  if (outcome.cutback_failed)
    texts.error = me + "in " + n(c.iterations) + " iterations per step, not even as " + sub +
        " (convergence measure " + general_format(outcome.result.measure, 3) + " > tolerance " +
        general_format(outcome.result.tolerance, 3) +
        "): raise iterations, lower the time step, or accept unconverged steps with "
        "'unconverged warn'";
  else if (outcome.reach_first)
    texts.note = "Fix sissm " + c.id + ": step " + n(c.step) +
        " went beyond the reach of the contact candidates of the last neighbor list build; "
        "redone as " +
        sub + " (counted in f_" + c.id + "[6])\n";
  else
    texts.note = me + "in " + n(c.iterations) + " iterations; redone as " + sub +
        " (counted in f_" + c.id + "[6])\n";
  return texts;
}

std::string unconverged_cause(double measure, double tol_step)
{
  return "this step stopped at the iteration limit with convergence measure " +
      general_format(measure, 3) + " above the tolerance " + general_format(tol_step, 3) +
      ", so the motion may be an artefact of the unconverged solve";
}

std::string unconverged_error(const StepContext &c, int evaluations, double measure,
                              double tol_step)
{
  return "Fix sissm " + c.id + ": step " + n(c.step) + " stopped at " + n(evaluations) +
      " iterations with convergence measure " + general_format(measure, 3) + " > tolerance " +
      general_format(tol_step, 3) + " (unconverged error)";
}

std::string unconverged_warning(const StepContext &c, int evaluations, double measure,
                                double tolerance)
{
  return "Fix sissm: step " + n(c.step) + " stopped at " + n(evaluations) +
      " iterations with convergence measure " + general_format(measure, 3) + " > tolerance " +
      general_format(tolerance, 3) + " (counted in f_" + c.id + "[4]; reported once per run)";
}

std::string roundoff_warning(long long step, double reach, double floor, double tolerance)
{
  return "Fix sissm: at step " + n(step) + " round-off in the atom coordinates (up to " +
      general_format(reach, 3) + " from the origin) limits the convergence measure to about " +
      general_format(floor, 3) + ", above the tolerance " + general_format(tolerance, 3) +
      ": steps that reach it count as converged (a body nearer the origin, or a smaller time "
      "step, allows a tighter tolerance; reported once per run)";
}

void StepStatistics::end_step(int count, double measure, int substeps, bool converged, double error)
{
  last_error = error >= 0.0 ? error : 0.0;
  if (error >= 0.0) by_error++;
  last_evaluations = count;
  last_measure = measure;
  last_substeps = substeps;
  steps++;
  evaluations += count;
  if (!converged) unconverged++;
}

double StepStatistics::output(int n) const
{
  const double average = steps ? (double) evaluations / steps : 0.0;
  const double values[11] = {(double) last_evaluations,
                             last_measure,
                             average,
                             (double) unconverged,
                             (double) last_substeps,
                             (double) cutback,
                             (double) last_krylov,
                             (double) last_newton,
                             (double) switches,
                             last_error,
                             (double) by_error};
  return values[n];
}

std::string StepStatistics::summary(const std::string &id) const
{
  return "Fix sissm " + id + " run: " + n(steps) + " steps, " +
      general_format((double) evaluations / steps, 6) + " iterations per step, " + n(unconverged) +
      " unconverged, " + n(cutback) + " cut back, " + n(switches) + " preconditioner switches" +
      (by_error > 0 ? ", " + n(by_error) + " ended by the error estimate" : "");
}

}    // namespace PeriSISSM
