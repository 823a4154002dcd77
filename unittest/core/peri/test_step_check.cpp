// The time step check of explicit runs (peri/step_check.h): which integrator styles it covers,
// the smallest estimate and the count above the time step over the masked rows only, and the
// warning's numbers.
#include "peri/step_check.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

using namespace PeriSISSM;

TEST(StepCheck, ExplicitIntegratorsAreThoseMovingAtomsByTheirForces)
{
  for (const char *style : {"nve", "nvt", "npt", "nph", "nve/limit", "nve/sphere", "langevin/nve"})
    EXPECT_TRUE(explicit_integrator(style)) << style;
  for (const char *style :
       {"sissm", "move", "nve/noforce", "rigid", "rigid/small", "rigid/nve", "rigid/nvt/small"})
    EXPECT_FALSE(explicit_integrator(style)) << style;
}

TEST(StepCheck, SmallestAndCountOverTheMaskedRows)
{
  const double inf = std::numeric_limits<double>::infinity();
  // rows 0..5; bits 2 and 4 integrated, bit 1 not
  const double dt[6] = {1.0e-8, 3.0e-7, 2.0e-7, inf, 1.0e-7, 5.0e-7};
  const int mask[6] = {1, 2 | 1, 4, 2, 2, 4};
  const StepExcess excess = step_excess(6, dt, mask, 2 | 4, 2.5e-7);
  EXPECT_EQ(excess.smallest, 1.0e-7);    // row 0 (1e-8) is not integrated
  EXPECT_EQ(excess.above, 2);            // rows 2 and 4
  EXPECT_EQ(excess.counted, 5);          // rows 1-5, the one without stiffness included
  // a time step equal to the smallest estimate is not above it
  EXPECT_EQ(step_excess(6, dt, mask, 2 | 4, 1.0e-7).above, 0);
  EXPECT_EQ(step_excess(6, dt, mask, 2 | 4, 1.0000001e-7).above, 1);
  // no integrated row: +infinity, nothing counted
  const StepExcess none = step_excess(6, dt, mask, 8, 1.0);
  EXPECT_EQ(none.smallest, inf);
  EXPECT_EQ(none.above, 0);
  EXPECT_EQ(none.counted, 0);
  EXPECT_EQ(step_excess(0, dt, mask, 2, 1.0).counted, 0);
}

TEST(StepCheck, WarningNamesStepEstimateCountsFixesAndRemedies)
{
  const std::string text = step_warning(1.0e-7, 9.4987e-8, 1234, 40000, "integrate (nve)");
  EXPECT_EQ(text.rfind("Pair peri/nosb: timestep 1e-07 is above the estimated stable explicit "
                       "time step 9.499e-08 of 1234 of the 40000 particles integrated by fix "
                       "integrate (nve)",
                       0),
            0u)
      << text;
  EXPECT_NE(text.find("Use a timestep below 9.499e-08"), std::string::npos) << text;
  EXPECT_NE(text.find("fix sissm"), std::string::npos) << text;
  EXPECT_NE(text.find("compute nosb/atom column 11"), std::string::npos) << text;
}
