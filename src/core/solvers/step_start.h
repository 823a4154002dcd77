// The start of an implicit step, kept so that the step can be redone from it (a cut-back, a
// switch of preconditioner: solvers/step_retry.h), and the rows outside the group placed within
// the step: they are at the end of the step already (held, or moved by another integrator), and
// sit where their velocity puts them at the time of a sub-step or of a scheme's forces.

#ifndef PERISISSM_SOLVERS_STEP_START_H
#define PERISISSM_SOLVERS_STEP_START_H

#include "solvers/system.h"

namespace PeriSISSM {

struct StepStart {
  double **x = nullptr;       // positions at the start (rows outside the group: at the end)
  double **v = nullptr;       // velocities at the start
  double **hist = nullptr;    // the time scheme's history at the start (ncols per row)
  int ncols = 0;
};

// x, v and the history of the first n rows (of the group or not) into start
void keep_start(int n, double **x, double **v, double **hist, const StepStart &start);

// with a time scheme's history (ncols columns, solvers/time_scheme.h): the force density at the
// start f into fstart for the rows of the group, which starts the history of those that have
// none; a row outside the group has none when it joins (its last column 0)
void keep_start_force(const Rows &rows, double **f, double **fstart, double **hist, int ncols);

// the rows of the group back at the start
void restore_start(const Rows &rows, const StepStart &start, double **x, double **v, double **hist);

// the rows outside the group at the fraction t of the step of length dt:
// x = x_end - (1 - t) dt v
void place_others(const Rows &rows, const StepStart &start, double **v, double dt, double t,
                  double **x);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_STEP_START_H
