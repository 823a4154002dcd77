// Which forces of other fixes an implicit step re-evaluates (solvers/external_forces.h): each
// property that lags a fix, and the mode of the step for each mix of roles.

#include "solvers/external_forces.h"

#include <gtest/gtest.h>

namespace {

using namespace PeriSISSM;

TEST(ExternalForces, RoleOfAFix)
{
  ExternalFix plain;
  EXPECT_EQ(external_role(plain), ExternalRole::may_rewrite);    // viscous, setforce
  ExternalFix potential;
  potential.potential = true;
  EXPECT_EQ(external_role(potential), ExternalRole::adds);    // gravity, walls, restrain
  for (int which = 0; which < 5; which++) {
    ExternalFix f = potential;
    if (which == 0) f.integrator = true;
    if (which == 1) f.dynamic_group = true;
    if (which == 2) f.reservoir = true;
    if (which == 3) f.keeps_state = true;
    if (which == 4) f.named_lagged = true;
    EXPECT_EQ(external_role(f), ExternalRole::lagged) << which;
    f.potential = false;
    EXPECT_EQ(external_role(f), ExternalRole::lagged) << which;
  }
}

TEST(ExternalForces, ModeOfTheStep)
{
  const auto A = ExternalRole::adds, W = ExternalRole::may_rewrite, L = ExternalRole::lagged;
  EXPECT_EQ(external_mode({}, true), ExternalMode::none);
  EXPECT_EQ(external_mode({}, false), ExternalMode::none);
  EXPECT_EQ(external_mode({A, W}, true), ExternalMode::implicit);
  EXPECT_EQ(external_mode({A, W}, false), ExternalMode::lagged);
  EXPECT_EQ(external_mode({L}, true), ExternalMode::mixed);
  EXPECT_EQ(external_mode({A, L, A}, true), ExternalMode::mixed);
  EXPECT_EQ(external_mode({A, L, W}, true), ExternalMode::lagged);
  EXPECT_EQ(external_mode({W, L}, true), ExternalMode::lagged);
  EXPECT_EQ(external_mode({L, A}, false), ExternalMode::lagged);
}

}    // namespace
