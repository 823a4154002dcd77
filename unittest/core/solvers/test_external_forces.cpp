// Which forces of other fixes an implicit step re-evaluates (solvers/external_forces.h): each
// property that lags a fix, and the mode of the step for each mix of roles.

#include "solvers/external_forces.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

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

ExternalFix fix(const std::string &id, const std::string &style, bool potential)
{
  ExternalFix f;
  f.id = id;
  f.style = style;
  f.post_force = true;
  f.potential = potential;
  return f;
}

TEST(ExternalForces, ChoiceOrdersDynamicGroupsFirstAndSkipsOthers)
{
  ExternalFix integrator = fix("int", "sissm", false);
  integrator.post_force = false;    // fix sissm itself acts in post_integrate
  ExternalFix group = fix("dyn", "GROUP", false);
  group.dynamic_group = true;
  const ExternalChoice c = choose_external(
      {integrator, fix("g", "gravity", true), group, fix("w", "wall", true)}, {}, true, "int");
  EXPECT_EQ(c.problem, "");
  EXPECT_EQ(c.mode, ExternalMode::mixed);    // the dynamic group next to none that rewrites
  EXPECT_EQ(c.implicit, (std::vector<int>{1, 3}));
  EXPECT_EQ(c.note.rfind("Fix sissm int: fix dyn (GROUP) may hold state", 0), 0u);
  EXPECT_EQ(c.refusal, "");
  const ExternalChoice d = choose_external(
      {integrator, fix("g", "gravity", true), fix("v", "viscous", false)}, {}, true, "int");
  EXPECT_EQ(d.mode, ExternalMode::implicit);
  EXPECT_EQ(d.implicit, (std::vector<int>{1, 2}));
  EXPECT_EQ(d.note, "");
  EXPECT_EQ(choose_external({integrator}, {}, true, "int").mode, ExternalMode::none);
}

TEST(ExternalForces, ChoiceNotesLaggedFixes)
{
  const ExternalChoice mixed = choose_external(
      {fix("g", "gravity", true), fix("py", "python/invoke", true)}, {"py"}, true, "int");
  EXPECT_EQ(mixed.mode, ExternalMode::mixed);
  EXPECT_EQ(mixed.implicit, (std::vector<int>{0}));
  EXPECT_EQ(mixed.note,
            "Fix sissm int: fix py (python/invoke) may hold state or random numbers (an "
            "integrator, a dynamic group, a thermostat, a fix with restart state, or named by "
            "keyword lagged) and must act once per step: its force is lagged (taken at the start "
            "of each step); the other fixes' forces are implicit\n");
  ExternalFix thermostat = fix("lang", "langevin", false);
  thermostat.reservoir = true;
  const ExternalChoice lagged =
      choose_external({thermostat, fix("set", "setforce", false)}, {}, true, "int");
  EXPECT_EQ(lagged.mode, ExternalMode::lagged);
  EXPECT_EQ(lagged.note,
            "Fix sissm int: fix lang (langevin) may hold state or random numbers (an integrator, "
            "a dynamic group, a thermostat, a fix with restart state, or named by keyword "
            "lagged) and must act once per step, and fix set (setforce) declares no potential, "
            "so it may rewrite forces (as setforce does): the forces of all other fixes are "
            "lagged (taken at the start of each step, as with 'external lagged')\n");
  // asked for: nothing to explain
  EXPECT_EQ(choose_external({thermostat, fix("set", "setforce", false)}, {}, false, "int").note,
            "");
}

TEST(ExternalForces, ChoiceRefusesLaggedNamesThatAreNoForces)
{
  ExternalFix print = fix("p", "print", false);
  print.post_force = false;
  EXPECT_EQ(choose_external({print}, {"q"}, true, "int").problem,
            "Fix sissm int lagged: no fix with ID q");
  EXPECT_EQ(choose_external({print}, {"p"}, true, "int").problem,
            "Fix sissm int lagged: fix p (print) adds no force after the pair style");
}

TEST(ExternalForces, ChoiceRefusesLaggedContactThatMustIterate)
{
  ExternalFix contact = fix("c", "nosb/contact", true);
  contact.limits_moves = true;
  EXPECT_EQ(choose_external({contact}, {}, true, "int").refusal, "");
  EXPECT_EQ(choose_external({contact}, {}, false, "int").refusal,
            "Fix sissm int: fix c (nosb/contact) makes the implicit step collision-free, so its "
            "force must be re-evaluated at every iterate, but the forces of the other fixes are "
            "lagged here (keyword external lagged): remove that, or turn the collision check off "
            "(ccd no)");
  contact.adapts_stiffness = true;
  ExternalFix thermostat = fix("lang", "langevin", false);
  thermostat.reservoir = true;
  EXPECT_EQ(choose_external({thermostat, fix("set", "setforce", false), contact}, {}, true, "int")
                .refusal,
            "Fix sissm int: fix c (nosb/contact) adapts its stiffness to the implicit step (kappa "
            "auto), so its force must be re-evaluated at every iterate, but the forces of the "
            "other fixes are lagged here (a fix that may rewrite forces is present next to a "
            "lagged one; hold atoms by leaving them out of fix sissm's group instead): remove "
            "that, or give kappa as a number");
  // named lagged itself: the refusal follows
  EXPECT_NE(choose_external({contact}, {"c"}, true, "int").refusal, "");
}

}    // namespace
