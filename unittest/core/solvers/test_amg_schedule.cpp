// When precond amg sets its hierarchy up again (solvers/amg_schedule.h): each reason for a
// set-up with new values and for a new interpolation, and what refresh() says about the
// hierarchy in use.

#include "solvers/amg_schedule.h"

#include <gtest/gtest.h>

namespace {

using namespace PeriSISSM;

// a schedule whose hierarchy was made and set up once at force factor 2, the set-up costing 4
// applications
AmgSchedule set_up_once()
{
  AmgSchedule s;
  s.made_hierarchy();
  EXPECT_TRUE(s.setup_wanted(true, 2.0));    // never set up
  EXPECT_FALSE(s.begin_setup(true, false, 2.0));
  s.measured_setup(4.0, false);
  return s;
}

TEST(AmgSchedule, KeptWhileNothingChanged)
{
  AmgSchedule s = set_up_once();
  s.finished(2, 20, true);    // baseline: 10 per Newton step
  EXPECT_FALSE(s.setup_wanted(true, 2.0));
  s.finished(2, 44, true);    // 22 = 1.5 * 10 + 2 + 5: too many
  EXPECT_TRUE(s.setup_wanted(true, 2.0));
  EXPECT_TRUE(s.begin_setup(true, false, 2.0));    // and with a new interpolation
  EXPECT_EQ(s.summary(),
            "2 set-ups of the AMG hierarchy (1 with new aggregates and "
            "interpolation)");
}

TEST(AmgSchedule, LaggingValuesAreSetUpOnceTheyCostASetUp)
{
  AmgSchedule s = set_up_once();
  s.finished(2, 20, true);    // baseline 10 per Newton step
  // (each solve asks first: the schedule counts the solves that used the hierarchy)
  for (int krylov : {12, 9, 12}) {    // 2, none (fewer), 2: 4 beyond it, the set-up's cost
    EXPECT_FALSE(s.setup_wanted(true, 2.0));
    s.finished(1, krylov, true);
  }
  EXPECT_FALSE(s.setup_wanted(true, 2.0));
  s.finished(1, 11, true);    // 5: more
  EXPECT_TRUE(s.setup_wanted(true, 2.0));
  EXPECT_FALSE(s.begin_setup(true, false, 2.0));    // new values, the interpolation kept
  s.measured_setup(1.0, true);                      // cheaper than the first
  s.finished(1, 16, true);
  // the values' baseline is now 16; the interpolation's is still 10 (a new one above 17)
  EXPECT_FALSE(s.setup_wanted(true, 2.0));
  s.finished(1, 17, true);
  EXPECT_FALSE(s.setup_wanted(true, 2.0));
  s.finished(1, 18, true);
  EXPECT_TRUE(s.setup_wanted(true, 2.0));
  EXPECT_TRUE(s.begin_setup(true, false, 2.0));
  s.made_hierarchy();
  s.measured_setup(50.0, false);    // a new interpolation: new values still cost 1
  s.finished(1, 10, true);
  EXPECT_FALSE(s.setup_wanted(true, 2.0));
  s.finished(1, 11, true);
  EXPECT_FALSE(s.setup_wanted(true, 2.0));
  s.finished(1, 11, true);    // 2 beyond the baseline of 10
  EXPECT_TRUE(s.setup_wanted(true, 2.0));
  EXPECT_EQ(s.summary(),
            "3 set-ups of the AMG hierarchy (2 with new aggregates and "
            "interpolation)");
}

TEST(AmgSchedule, ForceFactorPatternFailureAndMovedRows)
{
  AmgSchedule s = set_up_once();
  s.finished(1, 10, true);
  EXPECT_TRUE(s.setup_wanted(true, 3.0));           // another step length
  EXPECT_FALSE(s.begin_setup(true, false, 3.0));    // the interpolation is kept
  s.finished(1, 10, true);
  s.made_hierarchy();    // a new pattern: its hierarchy was made with it
  EXPECT_TRUE(s.setup_wanted(false, 3.0));
  EXPECT_FALSE(s.begin_setup(false, false, 3.0));
  s.finished(1, 10, false);    // not converged: set up again, keeping the interpolation
  EXPECT_TRUE(s.setup_wanted(true, 3.0));
  EXPECT_FALSE(s.begin_setup(true, false, 3.0));
  s.finished(1, 10, false);
  // the rows moved to other processes: numbered again, with a new interpolation
  EXPECT_TRUE(s.setup_wanted(true, 3.0));
  EXPECT_TRUE(s.begin_setup(true, true, 3.0));
  EXPECT_EQ(s.summary(),
            "5 set-ups of the AMG hierarchy (2 with new aggregates and "
            "interpolation)");
}

TEST(AmgSchedule, RefreshTellsWhetherTheHierarchyWasOld)
{
  AmgSchedule s = set_up_once();
  s.finished(1, 10, true);                         // the solve that made and set it up
  EXPECT_FALSE(s.refresh());                       // a fresh hierarchy: a new one would not help
  EXPECT_TRUE(s.setup_wanted(true, 2.0));          // refresh: set up again
  EXPECT_TRUE(s.begin_setup(true, false, 2.0));    // with a new interpolation
  s.made_hierarchy();
  s.finished(1, 10, true);
  EXPECT_FALSE(s.setup_wanted(true, 2.0));    // kept into the next solve
  s.finished(1, 10, true);
  EXPECT_TRUE(s.refresh());    // that solve used a hierarchy of an earlier one
  AmgSchedule unused = set_up_once();
  unused.finished(0, 0, true);
  unused.finished(0, 0, true);    // a solve that never used it
  EXPECT_FALSE(unused.refresh());
  EXPECT_EQ(AmgSchedule().summary(),
            "0 set-ups of the AMG hierarchy (0 with new aggregates and interpolation)");
}

}    // namespace
