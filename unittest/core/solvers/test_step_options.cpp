// The options of an implicit integrator's step (solvers/step_options.h): the words of the
// choices, the ranges of the values, the refused combinations and jacobi's preconditioner.

#include "solvers/step_options.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace PeriSISSM;

TEST(StepOptions, ChoicesAreFoundInTheOrderOfTheirEnums)
{
  EXPECT_EQ(choice_index("krylov", kSolverWords), (int) SolverKind::krylov);
  EXPECT_EQ(choice_index("amg", kPrecondWords), (int) PrecondKind::amg);
  EXPECT_EQ(choice_index("cutback", kUnconvergedWords), (int) Unconverged::cutback);
  EXPECT_EQ(choice_index("warn", kUnconvergedWords), (int) Unconverged::warn);
  EXPECT_EQ(choice_index("lagged", kExternalWords), 1);
  EXPECT_EQ(choice_index("newmark", kSchemeWords), -1);
  EXPECT_EQ(choice_index("Krylov", kSolverWords), -1);
}

TEST(StepOptions, ChoiceTextListsTheWords)
{
  EXPECT_EQ(choice_text(kSolverWords), "jacobi or krylov");
  EXPECT_EQ(choice_text(kUnconvergedWords), "warn, error or cutback");
  EXPECT_EQ(choice_text({"one"}), "one");
}

TEST(StepOptions, KeywordsAreKnown)
{
  for (const char *k : {"iterations", "tolerance", "relax", "solver", "external", "lagged",
                        "precond", "unconverged", "scheme"})
    EXPECT_TRUE(is_step_keyword(k)) << k;
  EXPECT_FALSE(is_step_keyword("petsc"));
  EXPECT_FALSE(is_step_keyword("1e-6"));
}

TEST(StepOptions, DefaultsAreValid)
{
  StepOptions o;
  for (const std::string &k : kStepKeywords) EXPECT_EQ(value_problem(o, k), "") << k;
  EXPECT_EQ(settle(o), "");
  EXPECT_EQ(o.precond, PrecondKind::amg);
}

TEST(StepOptions, ValuesOutOfRangeAreNamed)
{
  StepOptions o;
  o.iterations = 0;
  EXPECT_EQ(value_problem(o, "iterations"), "iterations must be >= 1");
  EXPECT_EQ(value_problem(o, "tolerance"), "");    // only the keyword just read is checked
  o.tolerance = -1e-9;
  EXPECT_EQ(value_problem(o, "tolerance"), "tolerance must be >= 0");
  o.tolerance = 0.0;
  EXPECT_EQ(value_problem(o, "tolerance"), "");
  o.retry.max_cutback = 21;
  EXPECT_EQ(value_problem(o, "unconverged"), "unconverged cutback levels must be 1 to 20");
  o.retry.max_cutback = 20;
  EXPECT_EQ(value_problem(o, "unconverged"), "");
  o.rho_inf = 1.5;
  EXPECT_EQ(value_problem(o, "scheme"), "scheme genalpha rho_inf must be 0 to 1");
  o.rho_inf = 0.0;
  EXPECT_EQ(value_problem(o, "scheme"), "");
}

TEST(StepOptions, NanValuesAreRefused)
{
  StepOptions o;
  o.tolerance = std::nan("");
  o.rho_inf = std::nan("");
  EXPECT_NE(value_problem(o, "tolerance"), "");
  EXPECT_NE(value_problem(o, "scheme"), "");
}

TEST(StepOptions, SettleRefusesCombinationsAndGivesJacobiTheBlocks)
{
  StepOptions o;
  o.relax = true;
  EXPECT_EQ(settle(o), "relax yes requires solver jacobi");
  o.solver = SolverKind::jacobi;
  EXPECT_EQ(settle(o), "");
  EXPECT_EQ(o.precond, PrecondKind::block);    // the default amg, not asked for
  StepOptions a;
  a.solver = SolverKind::jacobi;
  a.precond_given = true;
  EXPECT_EQ(settle(a).rfind("precond amg needs solver krylov", 0), 0u);
  a.precond = PrecondKind::block;
  EXPECT_EQ(settle(a), "");
}

}    // namespace
