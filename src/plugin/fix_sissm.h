/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm: the semi-implicit successive substitution method, a per-particle Jacobi
   fixed-point iteration whose fixed point is the backward-Euler step of pair peri/nosb, and
   its Krylov acceleration (Newton steps solved by conjugate gradients preconditioned with
   the same per-particle blocks).
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
  enum { JACOBI, KRYLOV };
  class PairPeriNosb *pair;
  int solver;           // JACOBI sweeps or KRYLOV (Newton-CG, SISSM blocks as preconditioner)
  int maxiter;          // force evaluations per step at most
  double tolerance;     // convergence: max_i |r_i| / (rho_i V_i^(1/3)) below it
  int relax;            // 1: per-particle step factor alpha_i, 0: alpha_i = 1 (jacobi)
  int implicit_external;    // 1: other fixes' post_force re-evaluated at every iterate
  double dtv;

  // statistics (global vector)
  int last_iterations;
  double last_measure;
  bigint nsteps_run, iterations_run, unconverged_run;

  int warned;           // non-convergence already reported in this run
  int nmax;
  int evaluations;      // force evaluations of the current step
  double **fint;        // internal force density at y^n (captured in pre_reverse; lagged)
  double **yn;          // y^n of owned atoms
  double **yhat;        // predictor y^n + h v^n (+ h^2 f_ext / rho when lagged)
  double **res;         // backward-Euler residual of the last evaluation
  double **block;       // implicit block sum_j omega_ij (H_i + H_j + S_ij) per owned atom
  double **rprev, **dprev;   // relax: residual and correction of the previous sweep
  double **xbase, **rbase, **jbase, **cres, **zdir, **pdir, **sdir;   // krylov vectors
  double *term;         // krylov: per-atom terms of a global sum

  void grow();
  void destroy_arrays();
  void capture_internal_force();
  void evaluate(int blocks);
  void particle_block(int i, double D[6]) const;
  void precondition(double **r, double **z);
  double dot(double **a, double **b);
  double reproducible_sum(const double *t, int n);
  double scaled_max(double **a, int per_density);
  double merit();
  void check_finite();
  void sweep(int first);
  double solve_jacobi();
  double solve_krylov();
};

}    // namespace LAMMPS_NS

#endif
#endif
