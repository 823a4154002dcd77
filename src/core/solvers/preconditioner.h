// Preconditioners of the Krylov solver: z = M^-1 r on the unknown rows.

#ifndef PERISISSM_SOLVERS_PRECONDITIONER_H
#define PERISISSM_SOLVERS_PRECONDITIONER_H

#include "solvers/system.h"

#include <string>

namespace PeriSISSM {

class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // a Newton step begins at the last evaluation (with blocks): a preconditioner that is built
  // from the current configuration is (re)built here
  virtual void prepare(NonlinearSystem &) {}
  // a time step's solve with this preconditioner ended (its Newton and Krylov counts, and
  // whether it converged): a preconditioner kept across time steps decides here whether it is
  // still good enough
  virtual void finished(int /*newton*/, int /*krylov*/, bool /*converged*/) {}
  // build again from the current configuration at the next prepare(); true when the one in
  // use was built from an earlier configuration (so a retry with a fresh one can help)
  virtual bool refresh() { return false; }
  // what it did over the run so far, for the log (empty: nothing to say)
  virtual std::string summary() const { return ""; }
  // z = M^-1 r estimates the distance to the solution for smooth and for local errors alike
  // (a matrix spectrally equivalent to J: keyword error may rely on it)
  virtual bool estimates_error() const { return false; }
  virtual void apply(NonlinearSystem &sys, double **r, double **z) = 0;
};

// The method's own: the per-particle 3x3 blocks of J (the SISSM correction D_i^-1 r_i).
class BlockPreconditioner : public Preconditioner {
 public:
  void apply(NonlinearSystem &sys, double **r, double **z) override;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_PRECONDITIONER_H
