// What an implicit integrator (fix sissm, doc/fix_sissm.rst) tells the log about its steps: the
// warnings, errors and notes built from the numbers of a step's solve (solvers/step_retry.h).
// Numbers are written as printf's %.3g and %.6g.

#ifndef PERISISSM_SOLVERS_STEP_REPORT_H
#define PERISISSM_SOLVERS_STEP_REPORT_H

#include "solvers/step_retry.h"

#include <string>

namespace PeriSISSM {

// the step the texts are about
struct StepContext {
  std::string id;        // the integrator's fix ID
  long long step = 0;    // the time step number
  int iterations = 0;    // the keyword iterations
  double dt = 0.0;       // the time step
};

// What the retry ladder did: warning (a switch of preconditioner; now_block: the block
// preconditioner is the one that redid the step), error (no cutback level converged), note (the
// step was cut back). Empty where it did not happen.
struct RetryTexts {
  std::string warning, error, note;
};
RetryTexts retry_texts(const RetryOutcome &outcome, const StepContext &c, bool now_block);

// An unconverged step: why its motion is doubtful (for contact), the error of unconverged
// error and the warning of unconverged warn (tolerance: the keyword's; tol_step: the step's).
std::string unconverged_cause(double measure, double tol_step);
std::string unconverged_error(const StepContext &c, int evaluations, double measure,
                              double tol_step);
std::string unconverged_warning(const StepContext &c, int evaluations, double measure,
                                double tolerance);

// The round-off floor of the convergence measure above the tolerance (solvers/step_tolerance.h;
// reach: the largest coordinate).
std::string roundoff_warning(long long step, double reach, double floor, double tolerance);

// The statistics of a run of steps (fix sissm's global vector, doc/fix_sissm.rst "Output").
struct StepStatistics {
  // the last step's evaluations, measure, sub-steps (1: not cut back), Newton steps and Krylov
  // iterations
  int last_evaluations = 0, last_substeps = 1, last_newton = 0, last_krylov = 0;
  double last_measure = 0.0;
  // the last step's estimated error over its motion where keyword error ended it (else 0)
  double last_error = 0.0;
  // the run's steps, evaluations, unconverged steps, steps cut back and steps redone with the
  // other preconditioner
  long long steps = 0, evaluations = 0, unconverged = 0, cutback = 0, switches = 0;
  // the run's steps that keyword error ended
  long long by_error = 0;

  void begin_step() { last_newton = last_krylov = 0; }
  // one solve of the step (a step redone counts all its solves)
  void solved(const SolveResult &r)
  {
    last_newton += r.newton;
    last_krylov += r.krylov;
  }
  // error: the estimated error over the motion where keyword error ended the step, < 0 if not
  void end_step(int evaluations, double measure, int substeps, bool converged, double error);
  // output n + 1 of the global vector: 1 the last step's evaluations, 2 its measure, 3 the
  // run's evaluations per step, 4 unconverged steps, 5 the last step's sub-steps, 6 steps cut
  // back, 7 the last step's Krylov iterations, 8 its Newton steps, 9 preconditioner switches,
  // 10 the last step's last_error, 11 the steps that keyword error ended
  double output(int n) const;
  // the run in one line of the log, without the newline (id: the integrator's fix ID)
  std::string summary(const std::string &id) const;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_STEP_REPORT_H
