// Which forces of other fixes an implicit step re-evaluates (external_forces.h).

#include "solvers/external_forces.h"

#include <algorithm>

namespace PeriSISSM {

ExternalRole external_role(const ExternalFix &fix)
{
  if (fix.integrator || fix.dynamic_group || fix.reservoir || fix.keeps_state || fix.named_lagged)
    return ExternalRole::lagged;
  return fix.potential ? ExternalRole::adds : ExternalRole::may_rewrite;
}

ExternalMode external_mode(const std::vector<ExternalRole> &roles, bool implicit_asked)
{
  if (roles.empty()) return ExternalMode::none;
  if (!implicit_asked) return ExternalMode::lagged;
  bool lagged = false, rewriting = false;
  for (ExternalRole role : roles) {
    lagged = lagged || role == ExternalRole::lagged;
    rewriting = rewriting || role == ExternalRole::may_rewrite;
  }
  if (!lagged) return ExternalMode::implicit;
  return rewriting ? ExternalMode::lagged : ExternalMode::mixed;
}

ExternalChoice choose_external(std::vector<ExternalFix> fixes,
                               const std::vector<std::string> &lagged, bool implicit_asked,
                               const std::string &integrator)
{
  ExternalChoice choice;
  const std::string me = "Fix sissm " + integrator;
  for (const std::string &name : lagged) {
    auto f = std::find_if(fixes.begin(), fixes.end(), [&](const ExternalFix &x) {
      return x.id == name;
    });
    if (f == fixes.end()) {
      choice.problem = me + " lagged: no fix with ID " + name;
      return choice;
    }
    if (!f->post_force) {
      choice.problem =
          me + " lagged: fix " + name + " (" + f->style + ") adds no force after the pair style";
      return choice;
    }
  }
  std::vector<ExternalRole> roles;
  std::vector<bool> iterate(fixes.size(), false);
  std::string lagged_names, rewriting_names;
  for (int pass = 0; pass < 2; pass++)
    for (size_t k = 0; k < fixes.size(); k++) {
      ExternalFix &f = fixes[k];
      if (!f.post_force || f.dynamic_group != (pass == 0)) continue;
      f.named_lagged = std::find(lagged.begin(), lagged.end(), f.id) != lagged.end();
      const ExternalRole role = external_role(f);
      roles.push_back(role);
      const std::string name = f.id + " (" + f.style + ")";
      if (role == ExternalRole::lagged) {
        lagged_names += (lagged_names.empty() ? "" : ", ") + name;
        continue;
      }
      if (role == ExternalRole::may_rewrite)
        rewriting_names += (rewriting_names.empty() ? "" : ", ") + name;
      choice.implicit.push_back((int) k);
      iterate[k] = true;
    }
  choice.mode = external_mode(roles, implicit_asked);

  const std::string lagged_why = me + ": fix " + lagged_names +
      " may hold state or random numbers (an integrator, a dynamic group, a thermostat, a fix "
      "with restart state, or named by keyword lagged) and must act once per step";
  if (choice.mode == ExternalMode::mixed)
    choice.note = lagged_why +
        ": its force is lagged (taken at the start of each step); the other fixes' forces are "
        "implicit\n";
  else if (choice.mode == ExternalMode::lagged && implicit_asked)
    choice.note = lagged_why + ", and fix " + rewriting_names +
        " declares no potential, so it may rewrite forces (as setforce does): the forces of all "
        "other fixes are lagged (taken at the start of each step, as with 'external lagged')\n";

  // contact that adapts its stiffness or limits the moves must be part of every iterate
  for (size_t k = 0; k < fixes.size() && choice.refusal.empty(); k++) {
    const ExternalFix &f = fixes[k];
    if (choice.mode != ExternalMode::lagged && iterate[k]) continue;
    std::string needs, remedy;
    if (f.adapts_stiffness) {
      needs = "adapts its stiffness to the implicit step (kappa auto)";
      remedy = "give kappa as a number";
    } else if (f.limits_moves) {
      needs = "makes the implicit step collision-free";
      remedy = "turn the collision check off (ccd no)";
    } else {
      continue;
    }
    choice.refusal = me + ": fix " + f.id + " (" + f.style + ") " + needs +
        ", so its force must be re-evaluated at every iterate, but the forces of the other fixes "
        "are lagged here (" +
        (implicit_asked ? "a fix that may rewrite forces is present next to a lagged one; hold "
                          "atoms by leaving them out of fix sissm's group instead"
                        : "keyword external lagged") +
        "): remove that, or " + remedy;
  }
  return choice;
}

}    // namespace PeriSISSM
