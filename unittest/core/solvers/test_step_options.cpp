// The options of an implicit integrator's step (solvers/step_options.h): the words of the
// choices, the ranges of the values, the refused combinations and jacobi's preconditioner.

#include "solvers/step_options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

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
                        "precond", "unconverged", "scheme", "chebyshev"})
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

// words become numbers by std::sto* whole; a word that is none throws, as LAMMPS's error does
double read_word(const std::string &w, WordKind kind)
{
  if (kind == WordKind::logical) {
    if (w != "yes" && w != "no") throw std::invalid_argument(w);
    return w == "yes" ? 1.0 : 0.0;
  }
  size_t end = 0;
  const double value = kind == WordKind::integer ? std::stoi(w, &end) : std::stod(w, &end);
  if (end != w.size()) throw std::invalid_argument(w);
  return value;
}

StepOptionsProblem read_words(const std::vector<std::string> &words, StepOptions &o)
{
  return read_step_options(words, read_word, o);
}

TEST(StepOptions, ReadsEveryKeyword)
{
  StepOptions o;
  const StepOptionsProblem p = read_words(
      {"iterations", "40", "tolerance", "1e-8", "solver", "jacobi", "relax", "yes", "external",
       "lagged", "lagged", "f1", "f2", "unconverged", "cutback", "6", "scheme", "genalpha", ".5"},
      o);
  EXPECT_EQ(p.missing, "");
  EXPECT_EQ(p.problem, "");
  EXPECT_EQ(o.iterations, 40);
  EXPECT_EQ(o.tolerance, 1e-8);
  EXPECT_EQ(o.solver, SolverKind::jacobi);
  EXPECT_TRUE(o.relax);
  EXPECT_FALSE(o.implicit_external);
  EXPECT_EQ(o.lagged, (std::vector<std::string>{"f1", "f2"}));
  EXPECT_EQ(o.retry.unconverged, Unconverged::cutback);
  EXPECT_EQ(o.retry.max_cutback, 6);
  EXPECT_EQ(o.scheme, "genalpha");
  EXPECT_EQ(o.rho_inf, 0.5);
  EXPECT_EQ(o.precond, PrecondKind::block);    // settled: jacobi sweeps use the blocks
  EXPECT_EQ(o.chebyshev, 0.0);                 // off unless asked for
  StepOptions c;
  EXPECT_EQ(read_words({"solver", "jacobi", "chebyshev", "0.95"}, c).problem, "");
  EXPECT_EQ(c.chebyshev, 0.95);
  StepOptions zero;
  EXPECT_EQ(read_words({"chebyshev", "0"}, zero).problem, "");    // 0: off, with any solver
  EXPECT_EQ(zero.chebyshev, 0.0);
}

TEST(StepOptions, ReadsPetscOptionsAndOptionalValues)
{
  StepOptions o;
  EXPECT_EQ(read_words({"precond", "amg", "petsc", "-pc_type lu", "scheme", "genalpha",
                        "unconverged", "cutback"},
                       o)
                .problem,
            "");
  EXPECT_TRUE(o.precond_given);
  EXPECT_EQ(o.petsc, "-pc_type lu");
  EXPECT_EQ(o.rho_inf, 0.8);            // genalpha's default rho_inf: the next word is a keyword
  EXPECT_EQ(o.retry.max_cutback, 4);    // cutback's default levels: no word follows
  StepOptions b;
  EXPECT_EQ(read_words({"scheme", "genalpha", "-0.5"}, b).problem,
            "scheme genalpha rho_inf must be 0 to 1, got -0.5");
}

TEST(StepOptions, ReadingNamesEachProblem)
{
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"iterations", "10", "speed", "2"},
       "unknown keyword 'speed' (allowed: iterations, tolerance, solver, precond, unconverged, "
       "scheme, relax, external, lagged, error, chebyshev)"},
      {{"iterations", "0"}, "iterations must be >= 1, got 0"},
      {{"tolerance", "-1"}, "tolerance must be >= 0, got -1"},
      {{"solver", "gmres"}, "solver must be jacobi or krylov, got 'gmres'"},
      {{"external", "explicit"}, "external must be implicit or lagged, got 'explicit'"},
      {{"precond", "multigrid"}, "precond must be block or amg, got 'multigrid'"},
      {{"precond", "block", "petsc", "-pc_type lu"}, "petsc options need precond amg"},
      {{"unconverged", "ignore"}, "unconverged must be warn, error or cutback, got 'ignore'"},
      {{"unconverged", "cutback", "30"}, "unconverged cutback levels must be 1 to 20, got 30"},
      {{"scheme", "newmark"}, "scheme must be euler, bdf2 or genalpha, got 'newmark'"},
      {{"scheme", "genalpha", "1.5"}, "scheme genalpha rho_inf must be 0 to 1, got 1.5"},
      {{"relax", "yes"}, "relax yes requires solver jacobi"},
      {{"chebyshev", "0.9"}, "chebyshev requires solver jacobi"},
      {{"solver", "jacobi", "chebyshev", "1"}, "chebyshev rho must be >= 0 and < 1, got 1"},
      {{"solver", "jacobi", "chebyshev", "-0.5"}, "chebyshev rho must be >= 0 and < 1, got -0.5"},
      {{"solver", "jacobi", "precond", "amg"},
       "precond amg needs solver krylov (the jacobi sweeps use the blocks themselves)"}};
  for (const auto &c : cases) {
    StepOptions o;
    const StepOptionsProblem p = read_words(c.first, o);
    EXPECT_EQ(p.problem, c.second) << c.first[0];
    EXPECT_EQ(p.missing, "") << c.first[0];
  }
}

TEST(StepOptions, ReadingNamesTheCommandWhoseArgumentsRanOut)
{
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"iterations"}, "fix sissm iterations"},
      {{"tolerance", "1e-6", "scheme"}, "fix sissm scheme"},
      {{"lagged", "solver", "krylov"}, "fix sissm lagged"},
      {{"precond", "amg", "petsc"}, "fix sissm precond amg petsc"}};
  for (const auto &c : cases) {
    StepOptions o;
    const StepOptionsProblem p = read_words(c.first, o);
    EXPECT_EQ(p.missing, c.second);
    EXPECT_EQ(p.problem, "");
  }
}

TEST(StepOptions, WordsThatAreNoNumbersGoToTheReader)
{
  StepOptions o;
  EXPECT_THROW(read_words({"iterations", "many"}, o), std::invalid_argument);
  EXPECT_THROW(read_words({"relax", "maybe"}, o), std::invalid_argument);
  EXPECT_THROW(read_words({"unconverged", "cutback", "9x"}, o), std::invalid_argument);
}

TEST(StepOptions, UnbentMembranesTakeBlockUnlessAmgWasAsked)
{
  StepOptions o;
  EXPECT_EQ(settle_for_membranes(o, false, "int"), "");
  EXPECT_EQ(o.precond, PrecondKind::amg);
  EXPECT_EQ(settle_for_membranes(o, true, "int"),
            "Fix sissm int: membranes without bending (pair_coeff ... membrane yes, no bend): "
            "precond block (the default amg has no out-of-plane stiffness for them; precond amg "
            "asks for it)\n");
  EXPECT_EQ(o.precond, PrecondKind::block);
  StepOptions asked;
  asked.precond_given = true;
  EXPECT_EQ(settle_for_membranes(asked, true, "int"), "");
  EXPECT_EQ(asked.precond, PrecondKind::amg);
}

// Keyword error: its default is on for the second-order schemes with the multigrid only (the
// block preconditioner's estimate misses smooth errors), an explicit value needs amg, and
// membranes without bending keep amg when it was asked for.
TEST(StepOptions, ErrorDefaultsToTheSchemeAndNeedsAmg)
{
  auto settled = [](const std::vector<std::string> &words, StepOptions &o) {
    return read_words(words, o).problem;
  };
  StepOptions euler, genalpha, bdf2, block, jacobi, given, bad, membrane;
  EXPECT_EQ(settled({}, euler), "");
  EXPECT_EQ(euler.error, 0.0);
  EXPECT_EQ(settled({"scheme", "genalpha"}, genalpha), "");
  EXPECT_EQ(genalpha.error, kDynamicsError);
  EXPECT_EQ(settled({"scheme", "bdf2"}, bdf2), "");
  EXPECT_EQ(bdf2.error, kDynamicsError);
  EXPECT_EQ(settled({"scheme", "genalpha", "precond", "block"}, block), "");
  EXPECT_EQ(block.error, 0.0);
  EXPECT_EQ(settled({"scheme", "bdf2", "solver", "jacobi"}, jacobi), "");
  EXPECT_EQ(jacobi.error, 0.0);
  EXPECT_EQ(settled({"error", "0.05"}, given), "");
  EXPECT_EQ(given.error, 0.05);
  EXPECT_EQ(settled({"error", "0.05", "precond", "block"}, bad),
            "error needs solver krylov with precond amg (the block preconditioner's estimate "
            "misses smooth errors by up to the ratio of stiffness to mass)");
  StepOptions range;
  EXPECT_EQ(settled({"error", "1"}, range), "error must be >= 0 and < 1, got 1");
  StepOptions off, tight, both;
  EXPECT_EQ(settled({"scheme", "genalpha", "error", "0"}, off), "");
  EXPECT_EQ(off.error, 0.0);
  // a tolerance asked for is the rule (no default error); both may be asked for
  EXPECT_EQ(settled({"scheme", "genalpha", "tolerance", "1e-9"}, tight), "");
  EXPECT_EQ(tight.error, 0.0);
  EXPECT_EQ(settled({"scheme", "bdf2", "tolerance", "1e-9", "error", "0.01"}, both), "");
  EXPECT_EQ(both.error, 0.01);
  // membranes without bending: the default amg becomes block and the rule goes off with it
  EXPECT_NE(settle_for_membranes(genalpha, true, "int"), "");
  EXPECT_EQ(genalpha.precond, PrecondKind::block);
  EXPECT_EQ(genalpha.error, 0.0);
  EXPECT_EQ(settle_for_membranes(given, true, "int"),
            "Fix sissm int: membranes without bending (pair_coeff ... membrane yes, no bend) with "
            "keyword error: precond amg kept (error needs it; without error these membranes take "
            "precond block)\n");
  EXPECT_EQ(given.precond, PrecondKind::amg);
}

}    // namespace
