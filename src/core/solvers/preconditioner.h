// Preconditioners of the Krylov solver: z = M^-1 r on the unknown rows.

#ifndef PERISISSM_SOLVERS_PRECONDITIONER_H
#define PERISISSM_SOLVERS_PRECONDITIONER_H

#include "solvers/system.h"

namespace PeriSISSM {

class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // a Newton step begins at the last evaluation (with blocks): a preconditioner that is built
  // from the current configuration is (re)built here
  virtual void prepare(NonlinearSystem &) {}
  virtual void apply(NonlinearSystem &sys, double **r, double **z) = 0;
};

// The method's own: the per-particle 3x3 blocks of J (the SISSM correction D_i^-1 r_i).
class BlockPreconditioner : public Preconditioner {
 public:
  void apply(NonlinearSystem &sys, double **r, double **z) override;
};

}  // namespace PeriSISSM

#endif  // PERISISSM_SOLVERS_PRECONDITIONER_H
