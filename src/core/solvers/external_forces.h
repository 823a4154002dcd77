// Which forces of other fixes an implicit step re-evaluates at every iterate (doc/fix_sissm.rst,
// keywords external and lagged). A fix that adds forces after the pair style (in post_force) is
// re-evaluated at every iterate unless it must act once per step: then its force is lagged,
// taken from the evaluation that ended the previous step. What decides it is what LAMMPS tells
// about the fix, and the user's list:
//   - an integrator (time_integrate) acts once per step: lagged;
//   - the fix of a dynamic group (LAMMPS's fix GROUP) changes the group: lagged;
//   - a fix that exchanges energy with a reservoir (ecouple_flag: thermostats such as fix
//     langevin, with random numbers and state): lagged;
//   - a fix that keeps a global state in restart files (restart_global: fix smd, spring/chunk):
//     lagged;
//   - a fix named in the keyword lagged (state, random numbers or callbacks LAMMPS does not flag,
//     e.g. fix python/invoke, fix external): lagged;
//   - any other is re-evaluated. One that declares a potential (energy_global_flag or
//     virial_global_flag: gravity, addforce, spring, walls, indent, restrain, nosb/contact ...)
//     adds a force that does not depend on the force so far; one that does not (viscous,
//     setforce, aveforce, enforce2d ...) may rewrite the force.
// The mode of the step follows: no such fixes (none); all re-evaluated, or all lagged by keyword
// external lagged (implicit, lagged); some lagged next to re-evaluated ones that all add forces
// (mixed: the lagged force is the sum the lagged fixes added); some lagged next to one that may
// rewrite the force, whose order relative to the lagged ones then matters (lagged: all of them).

#ifndef PERISISSM_SOLVERS_EXTERNAL_FORCES_H
#define PERISISSM_SOLVERS_EXTERNAL_FORCES_H

#include <string>
#include <vector>

namespace PeriSISSM {

// what LAMMPS tells about a fix (choose_external(): any fix; external_role(): one that acts in
// post_force)
struct ExternalFix {
  std::string id, style;
  bool post_force = false;       // acts in post_force
  bool integrator = false;       // time_integrate
  bool dynamic_group = false;    // the fix of a dynamic group
  bool reservoir = false;        // ecouple_flag
  bool keeps_state = false;      // restart_global
  bool potential = false;        // energy_global_flag or virial_global_flag
  bool named_lagged = false;     // named in fix sissm's keyword lagged
  // a contact of the implicit step (collision_limit.h) that adapts its stiffness to the step
  // (kappa auto), that makes the step collision-free
  bool adapts_stiffness = false, limits_moves = false;
};

enum class ExternalRole { adds, may_rewrite, lagged };

ExternalRole external_role(const ExternalFix &fix);

enum class ExternalMode { none, implicit, mixed, lagged };

// roles: of all fixes that act in post_force; implicit_asked: keyword external implicit
ExternalMode external_mode(const std::vector<ExternalRole> &roles, bool implicit_asked);

struct ExternalChoice {
  std::string problem;    // a name of keyword lagged that is no fix acting in post_force
  ExternalMode mode = ExternalMode::none;
  // the fixes re-evaluated at every iterate (places in the list), in the order LAMMPS calls
  // them in post_force: the dynamic-group fixes (style GROUP) first
  std::vector<int> implicit;
  std::string note;       // what to log about the choice (empty: nothing)
  std::string refusal;    // a contact that must be re-evaluated at every iterate but is lagged
};

// The roles of fixes (all of a LAMMPS instance, in their order; named_lagged is taken from
// lagged, the names of keyword lagged) and the mode of the step; the texts name the integrator
// ("Fix sissm ID: ...").
ExternalChoice choose_external(std::vector<ExternalFix> fixes,
                               const std::vector<std::string> &lagged, bool implicit_asked,
                               const std::string &integrator);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_EXTERNAL_FORCES_H
