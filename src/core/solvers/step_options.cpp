// The options of an implicit integrator's step and their rules (see step_options.h).

#include "solvers/step_options.h"

#include <cctype>

namespace PeriSISSM {

const std::vector<std::string> kStepKeywords = {"iterations",  "tolerance", "solver",   "precond",
                                                "unconverged", "scheme",    "relax",    "external",
                                                "lagged",      "error",     "chebyshev"};
const std::vector<std::string> kSolverWords = {"jacobi", "krylov"};
const std::vector<std::string> kPrecondWords = {"block", "amg"};
const std::vector<std::string> kExternalWords = {"implicit", "lagged"};
const std::vector<std::string> kUnconvergedWords = {"warn", "error", "cutback"};
const std::vector<std::string> kSchemeWords = {"euler", "bdf2", "genalpha"};

bool is_step_keyword(const std::string &word)
{
  return choice_index(word, kStepKeywords) >= 0;
}

int choice_index(const std::string &word, const std::vector<std::string> &words)
{
  for (size_t k = 0; k < words.size(); k++)
    if (words[k] == word) return (int) k;
  return -1;
}

std::string choice_text(const std::vector<std::string> &words)
{
  std::string text;
  for (size_t k = 0; k < words.size(); k++)
    text += (k == 0 ? "" : k + 1 == words.size() ? " or " : ", ") + words[k];
  return text;
}

std::string value_problem(const StepOptions &o, const std::string &keyword)
{
  if (keyword == "iterations" && o.iterations < 1) return "iterations must be >= 1";
  if (keyword == "tolerance" && !(o.tolerance >= 0.0)) return "tolerance must be >= 0";
  if (keyword == "error" && o.error_given && !(o.error >= 0.0 && o.error < 1.0))
    return "error must be >= 0 and < 1";
  if (keyword == "unconverged" && (o.retry.max_cutback < 1 || o.retry.max_cutback > 20))
    return "unconverged cutback levels must be 1 to 20";
  if (keyword == "scheme" && !(o.rho_inf >= 0.0 && o.rho_inf <= 1.0))
    return "scheme genalpha rho_inf must be 0 to 1";
  if (keyword == "chebyshev" && !(o.chebyshev >= 0.0 && o.chebyshev < 1.0))
    return "chebyshev rho must be >= 0 and < 1";
  return "";
}

std::string settle(StepOptions &o)
{
  if (o.relax && o.solver != SolverKind::jacobi) return "relax yes requires solver jacobi";
  if (o.chebyshev > 0.0 && o.solver != SolverKind::jacobi)
    return "chebyshev requires solver jacobi";
  if (o.solver == SolverKind::jacobi && o.precond_given && o.precond == PrecondKind::amg)
    return "precond amg needs solver krylov (the jacobi sweeps use the blocks themselves)";
  if (o.solver == SolverKind::jacobi) o.precond = PrecondKind::block;
  if (o.error > 0.0 && o.precond != PrecondKind::amg)
    return "error needs solver krylov with precond amg (the block preconditioner's estimate "
           "misses smooth errors by up to the ratio of stiffness to mass)";
  if (o.error < 0.0)
    o.error = (o.scheme != "euler" && o.precond == PrecondKind::amg && !o.tolerance_given)
        ? kDynamicsError
        : 0.0;
  return "";
}

std::string settle_for_membranes(StepOptions &o, bool unbent_membranes, const std::string &id)
{
  if (o.precond_given || o.precond != PrecondKind::amg || !unbent_membranes) return "";
  if (o.error_given && o.error > 0.0)
    return "Fix sissm " + id +
        ": membranes without bending (pair_coeff ... membrane yes, no bend) with keyword error: "
        "precond amg kept (error needs it; without error these membranes take precond block)\n";
  o.precond = PrecondKind::block;
  o.error = 0.0;
  return "Fix sissm " + id +
      ": membranes without bending (pair_coeff ... membrane yes, no bend): precond block (the "
      "default amg has no out-of-plane stiffness for them; precond amg asks for it)\n";
}

namespace {

  // the value after a choice: unconverged cutback's levels, genalpha's rho_inf
  bool starts_number(const std::string &word, bool real)
  {
    const unsigned char c = word.empty() ? 0 : word[0];
    return std::isdigit(c) || (real && (c == '.' || c == '-'));
  }

}    // namespace

StepOptionsProblem read_step_options(const std::vector<std::string> &words, const WordReader &read,
                                     StepOptions &o)
{
  const size_t n = words.size();
  size_t at = 0;
  while (at < n) {
    const std::string key = words[at];
    if (!is_step_keyword(key)) {
      std::string allowed;
      for (const std::string &k : kStepKeywords) allowed += (allowed.empty() ? "" : ", ") + k;
      return {"", "unknown keyword '" + key + "' (allowed: " + allowed + ")"};
    }
    if (at + 2 > n || (key == "lagged" && is_step_keyword(words[at + 1])))
      return {"fix sissm " + key, ""};
    std::string value = words[at + 1];
    at += 2;
    int k = 0;
    const std::vector<std::string> *choices = key == "solver" ? &kSolverWords
        : key == "external"                                   ? &kExternalWords
        : key == "precond"                                    ? &kPrecondWords
        : key == "unconverged"                                ? &kUnconvergedWords
        : key == "scheme"                                     ? &kSchemeWords
                                                              : nullptr;
    if (choices) {
      k = choice_index(value, *choices);
      if (k < 0) return {"", key + " must be " + choice_text(*choices) + ", got '" + value + "'"};
    }
    if (key == "iterations") {
      o.iterations = (int) read(value, WordKind::integer);
    } else if (key == "tolerance") {
      o.tolerance = read(value, WordKind::real);
      o.tolerance_given = true;
    } else if (key == "error") {
      o.error = read(value, WordKind::real);
      o.error_given = true;
    } else if (key == "relax") {
      o.relax = read(value, WordKind::logical) != 0.0;
    } else if (key == "chebyshev") {
      o.chebyshev = read(value, WordKind::real);
    } else if (key == "solver") {
      o.solver = (SolverKind) k;
    } else if (key == "external") {
      o.implicit_external = k == 0;
    } else if (key == "lagged") {
      // the fix IDs up to the next keyword
      for (at--; at < n && !is_step_keyword(words[at]); at++) o.lagged.push_back(words[at]);
    } else if (key == "precond") {
      o.precond_given = true;
      o.precond = (PrecondKind) k;
      if (at < n && words[at] == "petsc") {
        if (at + 2 > n) return {"fix sissm precond amg petsc", ""};
        if (o.precond != PrecondKind::amg) return {"", "petsc options need precond amg"};
        o.petsc = words[at + 1];
        at += 2;
      }
    } else if (key == "unconverged") {
      o.retry.unconverged = (Unconverged) k;
      if (o.retry.unconverged == Unconverged::cutback && at < n &&
          starts_number(words[at], false)) {
        value = words[at++];
        o.retry.max_cutback = (int) read(value, WordKind::integer);
      }
    } else if (key == "scheme") {
      o.scheme = kSchemeWords[k];
      if (o.scheme == "genalpha" && at < n && starts_number(words[at], true)) {
        value = words[at++];
        o.rho_inf = read(value, WordKind::real);
      }
    }
    const std::string bad = value_problem(o, key);
    if (!bad.empty()) return {"", bad + ", got " + value};
  }
  return {"", settle(o)};
}

}    // namespace PeriSISSM
