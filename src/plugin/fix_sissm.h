/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm: the semi-implicit successive substitution method, a per-particle Jacobi
   fixed-point iteration whose fixed point is the backward-Euler step of pair peri/nosb.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sissm,FixSissm);
// clang-format on
#else

#ifndef LMP_FIX_SISSM_H
#define LMP_FIX_SISSM_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSissm : public Fix {
 public:
  FixSissm(class LAMMPS *, int, char **);
  ~FixSissm() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_reverse(int, int) override;
  void pre_reverse(int, int) override;
  void post_integrate() override;
  void reset_dt() override;
  double compute_vector(int) override;
  double memory_usage() override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

 protected:
  class PairPeriNosb *pair;
  int maxiter;          // iterations per step at most
  double tolerance;     // convergence: max_i |y_i^{k+1} - y_i^k| / size_i below it
  int relax;            // 1: per-particle step factor alpha_i, 0: alpha_i = 1
  double dtv;

  // statistics (global vector)
  int last_iterations;
  double last_measure;
  bigint nsteps_run, iterations_run, unconverged_run;

  int warned;           // non-convergence already reported in this run
  int nmax;
  double **fint;        // internal force density at y^n (captured in pre_reverse)
  double **yn;          // y^n of owned atoms
  double **yhat;        // predictor y^n + h v^n + h^2 f_ext / rho
  double **rprev, **dprev;   // residual and correction of the previous iteration (relax)
  double **block;       // implicit block sum_j omega_ij (H_i + H_j + S_ij) per owned atom

  void grow();
  void capture_internal_force();
  void internal_force();
  double iterate(int first);
};

}    // namespace LAMMPS_NS

#endif
#endif
