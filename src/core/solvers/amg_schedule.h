// When precond amg sets its multigrid hierarchy up again (doc/fix_sissm.rst, "Preconditioners").
// A set-up costs a few force evaluations (new values: the Galerkin products again) to tens (new
// aggregates and interpolation), an application one or two, so the hierarchy is kept across
// Newton steps and time steps while it works. Two kinds of set-up:
// - new values, the interpolation kept: when the pattern or the force factor changed, after a
//   step that did not converge, and once the Krylov iterations beyond the rate of the first
//   step after the last set-up (per Newton step), summed over the steps since, exceed what a
//   set-up with new values costs (the break-even rule of renting against buying), counted in
//   applications of the hierarchy (measured_setup(); an iteration costs an application and a
//   force evaluation, so this waits longer than break-even). The values lag behind a moving
//   body: measured on a falling cloth of 33418 vertices, the iterations per Newton step grew
//   from 6 to 18 within 8 steps of one set-up;
// - a new interpolation (aggregates and prolongators) as well: after a step that did not
//   converge in a solve that used a hierarchy of an earlier one (refresh()), after a step whose
//   iterations per Newton step exceeded 1.5 times (+2) those of the first step after the
//   interpolation was made (an interpolation is only as good as the rigid-body modes and the
//   matrix it was made from), and when the caller's rows moved (the atoms of a fixed numbering
//   went to other processes). A neighbor list build that keeps the pattern keeps the
//   interpolation.

#ifndef PERISISSM_SOLVERS_AMG_SCHEDULE_H
#define PERISISSM_SOLVERS_AMG_SCHEDULE_H

#include <string>

namespace PeriSISSM {

class AmgSchedule {
 public:
  // a new hierarchy (aggregates and interpolation) was made
  void made_hierarchy();
  // a Newton step is about to use the hierarchy (same_pattern: the pattern is the one the
  // hierarchy has; c: the force factor): whether the matrix is to be set up again
  bool setup_wanted(bool same_pattern, double c);
  // the set-up begins (same_pattern: as for setup_wanted; moved: the unknowns' rows should be
  // numbered again): whether it needs a new hierarchy first
  bool begin_setup(bool same_pattern, bool moved, double c);
  // what the last set-up cost in applications of the hierarchy (values_only: it kept the
  // interpolation); the cost of new values is that of the last such set-up, until there is one
  // that of any set-up
  void measured_setup(double applications, bool values_only);
  // the solve ended (Preconditioner::finished; counts global)
  void finished(int newton, int krylov, bool converged);
  // set up again, with a new interpolation, at the next use; true when the solve used a
  // hierarchy or an interpolation made in an earlier solve
  bool refresh();
  // "S set-ups of the AMG hierarchy (P with new aggregates and interpolation)"
  std::string summary() const;

 private:
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
  double baseline_ = 0.0;           // Krylov iterations per Newton step of the first solve
                                    //   after the last set-up
  double interp_baseline_ = 0.0;    // and after the interpolation was made
  double excess_ = 0.0;             // Krylov iterations beyond baseline_ since the set-up
  double value_cost_ = 0.0;         // a set-up with new values, in applications
  bool value_cost_measured_ = false;    // on such a set-up
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_AMG_SCHEDULE_H
