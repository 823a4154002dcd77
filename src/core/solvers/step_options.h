// The options of an implicit integrator's step (doc/fix_sissm.rst, Syntax: the keywords of fix
// sissm) and their rules, apart from how an input script is read: the keywords, the words each
// choice accepts, the range of each value, and which combinations are refused.

#ifndef PERISISSM_SOLVERS_STEP_OPTIONS_H
#define PERISISSM_SOLVERS_STEP_OPTIONS_H

#include "solvers/step_retry.h"

#include <functional>
#include <string>
#include <vector>

namespace PeriSISSM {

// in the order of the words of kSolverWords and kPrecondWords
enum class SolverKind { jacobi, krylov };
enum class PrecondKind { block, amg };

struct StepOptions {
  int iterations = 100;       // force evaluations per step at most
  double tolerance = 1e-6;    // convergence: max_i |r_i| / (rho_i V_i^(1/3)) below it
  // keyword error: a step has also converged when the preconditioner's estimate of its
  // position error is below error times the step's largest motion (newton_krylov.h); -1 until
  // settle() gives the default (kDynamicsError for the second-order schemes with solver krylov
  // and precond amg where keyword tolerance was not given, 0 = off otherwise)
  double error = -1.0;
  bool error_given = false;
  bool tolerance_given = false;
  bool relax = false;    // jacobi: per-particle step factor alpha_i (false: alpha_i = 1)
  // jacobi: the estimated spectral radius of the sweep for its Chebyshev acceleration
  // (chebyshev.h; 0: plain sweeps)
  double chebyshev = 0.0;
  SolverKind solver = SolverKind::krylov;
  PrecondKind precond = PrecondKind::amg;
  bool precond_given = false;         // the keyword precond was given
  std::string petsc;                  // options for PETSc's preconditioner (precond amg)
  bool implicit_external = true;      // keyword external: implicit or lagged
  std::vector<std::string> lagged;    // keyword lagged: fixes that act once per step
  RetryPolicy retry;                  // keyword unconverged
  std::string scheme = "euler";       // keyword scheme, and generalized-alpha's rho_inf
  double rho_inf = 0.8;
};

// the default of keyword error for the second-order schemes (doc/fix_sissm.rst, "Stopping")
constexpr double kDynamicsError = 1e-3;

// the keywords, in the order an error message lists them
extern const std::vector<std::string> kStepKeywords;
// the words of each choice, in the order of their enum (the external ones: implicit, lagged)
extern const std::vector<std::string> kSolverWords, kPrecondWords, kExternalWords,
    kUnconvergedWords, kSchemeWords;

bool is_step_keyword(const std::string &word);
// the place of word in words, -1 when it is not one of them
int choice_index(const std::string &word, const std::vector<std::string> &words);
// "a, b or c"
std::string choice_text(const std::vector<std::string> &words);

// What is wrong with the value the keyword set (empty: nothing), e.g. "iterations must be >= 1";
// for unconverged the cutback levels, for scheme the rho_inf of genalpha.
std::string value_problem(const StepOptions &o, const std::string &keyword);

// The rules between keywords once all are read: the combination refused (empty: none), and
// otherwise solver jacobi takes precond block (its sweeps use the blocks themselves) and
// keyword error its default.
std::string settle(StepOptions &o);

// Membranes without bending (unbent_membranes): the coarse level's matrix has no stiffness out
// of their plane but the mass (with bending, the hinges give it one), and amg lets such a flat
// membrane leave its plane (measured: the hanging strip of examples/membranes buckles sideways in
// the first step and then misses the tolerance; block keeps it in its plane), so the default
// precond amg becomes block there, and the default of keyword error 0. Returns the note for the log of the integrator with fix ID id
// (empty: nothing changed).
std::string settle_for_membranes(StepOptions &o, bool unbent_membranes, const std::string &id);

// How a single word becomes a number of a kind, by the rules and error messages of the caller
// (LAMMPS: utils::inumeric, numeric, logical; a logical as 1 or 0); a word that is no such
// number does not return.
enum class WordKind { integer, real, logical };
using WordReader = std::function<double(const std::string &, WordKind)>;

// What reading the keywords found wrong (both empty: nothing): missing names the command whose
// arguments ran out ("fix sissm iterations"); problem what is illegal about the words.
struct StepOptionsProblem {
  std::string missing, problem;
};

// The keywords and values of words (those after "fix ID group sissm") read into o in their
// order, each value checked by value_problem() as it is read, then settle(o). A choice word,
// an unknown keyword or a missing value ends the reading with the problem.
StepOptionsProblem read_step_options(const std::vector<std::string> &words, const WordReader &read,
                                     StepOptions &o);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_STEP_OPTIONS_H
