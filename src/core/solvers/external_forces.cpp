// Which forces of other fixes an implicit step re-evaluates (external_forces.h).

#include "solvers/external_forces.h"

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

}    // namespace PeriSISSM
