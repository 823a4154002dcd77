// The options of an implicit integrator's step and their rules (see step_options.h).

#include "solvers/step_options.h"

namespace PeriSISSM {

const std::vector<std::string> kStepKeywords = {"iterations", "tolerance",   "solver",
                                                "precond",    "unconverged", "scheme",
                                                "relax",      "external",    "lagged"};
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
  if (keyword == "unconverged" && (o.retry.max_cutback < 1 || o.retry.max_cutback > 20))
    return "unconverged cutback levels must be 1 to 20";
  if (keyword == "scheme" && !(o.rho_inf >= 0.0 && o.rho_inf <= 1.0))
    return "scheme genalpha rho_inf must be 0 to 1";
  return "";
}

std::string settle(StepOptions &o)
{
  if (o.relax && o.solver != SolverKind::jacobi) return "relax yes requires solver jacobi";
  if (o.solver == SolverKind::jacobi && o.precond_given && o.precond == PrecondKind::amg)
    return "precond amg needs solver krylov (the jacobi sweeps use the blocks themselves)";
  if (o.solver == SolverKind::jacobi) o.precond = PrecondKind::block;
  return "";
}

}    // namespace PeriSISSM
