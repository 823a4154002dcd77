/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   The nonlinear system of fix sissm's step as the core's solvers see it (solvers/system.h):
   the owned atoms of the group, one evaluation a force evaluation (fix_sissm_system.cpp); and
   the reductions the solvers need, over LAMMPS's world communicator.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_SISSM_SYSTEM_H
#define LMP_FIX_SISSM_SYSTEM_H

#include "linalg/reductions.h"
#include "solvers/system.h"

#include <mpi.h>

namespace LAMMPS_NS {

class FixSissm;

// max and sum over a communicator; total_rows: the atoms of the LAMMPS instance
class WorldReductions : public PeriSISSM::Reductions {
 public:
  WorldReductions(class LAMMPS *lmp, MPI_Comm world) : lmp_(lmp), world_(world) {}
  void max(double *values, int n) override;
  void sum(long long *values, int n) override;
  double total_rows() const override;

 private:
  class LAMMPS *lmp_;
  MPI_Comm world_;
};

class SissmSystem : public PeriSISSM::NonlinearSystem {
 public:
  SissmSystem(FixSissm *fix, PeriSISSM::Reductions &reductions) : fix_(fix), reductions_(reductions)
  {
  }
  // the rows of this step (the group's owned atoms), set before each step
  PeriSISSM::Rows &step_rows() { return rows_; }
  // the evaluation count starts again (a new (sub-)step)
  void begin_solve() { evaluations_ = 0; }

  const PeriSISSM::Rows &rows() const override { return rows_; }
  PeriSISSM::Reductions &reductions() override { return reductions_; }
  double **unknowns() override;
  void evaluate(bool blocks) override;
  double **residual() override;
  int evaluations() const override { return evaluations_; }
  bool evaluation_complete() const override { return !contact_incomplete_; }
  bool stalled() const override { return stalled_; }
  void block(int i, double D[6]) const override;
  double step_tolerance() override;
  double **start() override;
  void check_finite() override;

 private:
  FixSissm *fix_;
  PeriSISSM::Reductions &reductions_;
  PeriSISSM::Rows rows_;
  int evaluations_ = 0;           // force evaluations of the current (sub-)step
  int contact_incomplete_ = 0;    // the last evaluation's contact candidates were incomplete
  bool stalled_ = false;          // the last evaluation's move stalled at a reach (stalled())
  // the contacts' diagonal blocks of the last evaluation with blocks are still to be added (at
  // the first block() after it, Jacobian probes in between or not: most iterates never ask for
  // them)
  mutable bool contact_blocks_due_ = false;
};

}    // namespace LAMMPS_NS

#endif
