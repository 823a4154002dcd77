// The block preconditioner (see preconditioner.h).

#include "solvers/preconditioner.h"

#include "linalg/small_matrix.h"

namespace PeriSISSM {

void BlockPreconditioner::apply(NonlinearSystem &sys, double **r, double **z)
{
  const Rows &rows = sys.rows();
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    double D[6];
    sys.block(i, D);
    solve_spd3(D, r[i], z[i]);
  }
}

}    // namespace PeriSISSM
