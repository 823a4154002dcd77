// When precond amg sets its multigrid hierarchy up again (doc/fix_sissm.rst, "Preconditioners").
// A set-up costs tens of force evaluations and an application one or two, so the hierarchy is
// kept across Newton steps and time steps while it works. The matrix is set up again when the
// pattern or the force factor changed, after a step that did not converge, and after a step
// whose Krylov iterations per Newton step exceeded 1.5 times (+2) those of the first step that
// used the set-up. A set-up keeps the interpolation (aggregates and prolongators) unless the
// pattern was built since it was made, a step failed, or the iterations grew as above: an
// interpolation is only as good as the rigid-body modes and the matrix it was made from
// (measured: a cloth falling from flat, the first step's interpolation kept to step 23, failed
// that step with values set up in it; a new interpolation converged it).

#ifndef PERISISSM_SOLVERS_AMG_SCHEDULE_H
#define PERISISSM_SOLVERS_AMG_SCHEDULE_H

#include <string>

namespace PeriSISSM {

class AmgSchedule {
 public:
  // a new hierarchy (aggregates and interpolation) was made for the pattern of build built
  void made_hierarchy(long long built);
  // a Newton step is about to use the hierarchy (same_pattern: the pattern is the one the
  // hierarchy has; c: the force factor): whether the matrix is to be set up again
  bool setup_wanted(bool same_pattern, double c);
  // the set-up begins (pattern of build built): whether it needs a new hierarchy first
  bool begin_setup(bool same_pattern, long long built, double c);
  // the solve ended (Preconditioner::finished; counts global)
  void finished(int newton, int krylov, bool converged);
  // set up again, with a new interpolation, at the next use; true when the solve used a
  // hierarchy or an interpolation made in an earlier solve
  bool refresh();
  // "S set-ups of the AMG hierarchy (P with new aggregates and interpolation)"
  std::string summary() const;

 private:
  long long interp_at_ = -1;     // the build of the pattern the interpolation was made for
  bool reinterp_ = false;        // the next set-up makes a new interpolation (a step failed)
  bool stale_ = true;            // set up again at the next use
  int solves_ = 0;               // solves that used the current set-up
  bool used_ = false;            // the solve under way applied the hierarchy
  bool fresh_ = false;           // and set it up
  bool fresh_interp_ = false;    // and made its aggregates and interpolation
  bool lagged_ = false;          // the last solve used a hierarchy (or its interpolation) made
                                 //   in an earlier one
  long long setups_ = 0, patterns_ = 0;    // set-ups so far, and those with a new hierarchy
  double set_factor_ = 0.0;                // the force factor at the last set-up
  double baseline_ = 0.0;                  // Krylov iterations per Newton step of its first solve
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_AMG_SCHEDULE_H
