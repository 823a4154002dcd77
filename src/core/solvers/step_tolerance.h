// The tolerance a step can meet (doc/fix_sissm.rst, keyword tolerance). Positions are absolute
// coordinates: a particle at |x| from the origin is known to eps |x| (eps the machine epsilon),
// and so are its bond vectors, so its force density is known to about |block_i| eps |x|, and
// the convergence measure (the residual as a length relative to the particle size l_i) to
//   floor_i = eps (|x_i| / l_i) (1 + c |block_i| / rho_i)
// with |x| the largest coordinate, |block| the largest diagonal entry of the particle's SISSM
// block (the row sum of its bond stiffnesses), c the time scheme's force factor (h^2 for
// backward Euler). Measured on a 4x3x3 block at 20 and 100 x the explicit limit (neo-Hookean,
// random velocities), at the origin and moved 4e4 particle sizes away, the measure stalls at
// 0.2 to 0.4 x this estimate (1e-12 at the origin, 2e-8 far away, at 20 x). A step whose
// measure is below the larger of the tolerance asked for and half the largest estimate counts
// as converged. Tolerance 0 asks for every step to use all its iterations: no floor then.

#ifndef PERISISSM_SOLVERS_STEP_TOLERANCE_H
#define PERISISSM_SOLVERS_STEP_TOLERANCE_H

#include "linalg/reductions.h"
#include "solvers/system.h"

namespace PeriSISSM {

struct StepTolerance {
  double tolerance = 0.0;    // the one the step is held to: max(asked, floor)
  double floor = 0.0;        // what round-off allows (0 when the tolerance asked is 0)
  double reach = 0.0;        // the largest coordinate of the rows (all processes)
  // round-off, not the tolerance asked for, decides when the step has converged
  bool roundoff_limited(double asked) const { return floor > asked; }
};

// floor_i / (eps / 2) of one particle: its position x, its block (xx yy zz xy xz yz; the bond
// part, without the density), size l_i = V_i^(1/3), density rho_i, force factor c
double roundoff_term(const double x[3], const double block[6], double size, double density,
                     double force_factor);

// The tolerance of a step over the unknown rows (rows.size and rows.density must be set), at
// positions x with the blocks of the last evaluation: one max over all processes (two values).
StepTolerance step_tolerance(double asked, const Rows &rows, double **x, double **block,
                             double force_factor, Reductions &reductions);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_STEP_TOLERANCE_H
