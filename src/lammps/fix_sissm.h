/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm: the semi-implicit successive substitution method, a per-particle Jacobi
   fixed-point iteration whose fixed point is the implicit step of pair peri/nosb (backward
   Euler, or the second-order BDF2 and generalized-alpha of keyword scheme), and its Krylov
   acceleration (Newton steps solved by conjugate gradients preconditioned with the same
   per-particle blocks or with PETSc's multigrid). The LAMMPS glue of the core's solvers
   (src/core/solvers): it owns the per-atom storage and runs the step's retry ladder; the
   nonlinear system the solvers see (fix_sissm_system.cpp) is its group's atoms, with the force
   model behind the ImplicitForces interface of the pair style.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sissm,FixSissm);
// clang-format on
#else

#ifndef LMP_FIX_SISSM_H
#define LMP_FIX_SISSM_H

#include "fix.h"

#include "solvers/external_forces.h"
#include "solvers/jacobi.h"
#include "solvers/step_options.h"
#include "solvers/time_scheme.h"

#include <memory>
#include <string>
#include <vector>

namespace PeriSISSM {
class Preconditioner;
}

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
  void post_run() override;
  void reset_dt() override;
  double compute_vector(int) override;
  double memory_usage() override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  // the time scheme's per-atom history (fix_sissm_history.cpp): it travels with the atoms and
  // is kept in restart files
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

 protected:
  class ImplicitForces *forces = nullptr;    // the pair style's side of the step
  // the nonlinear system the solvers see, and its reductions over world (fix_sissm_system.cpp)
  std::unique_ptr<class SissmSystem> system;
  std::unique_ptr<class WorldReductions> reductions;
  // of the Krylov solver: precond points at amg_precond (precond amg) or block_precond (precond
  // block, and a step that amg did not converge)
  PeriSISSM::Preconditioner *precond = nullptr;
  std::unique_ptr<PeriSISSM::Preconditioner> amg_precond, block_precond;
  std::unique_ptr<PeriSISSM::TimeScheme> scheme;    // which implicit step
  PeriSISSM::StepOptions opt;                       // the keywords (solvers/step_options.h)
  PeriSISSM::StepArrays arrays;                     // the per-atom arrays of the step being solved
  int ncols = 0;                // the scheme's per-atom history columns (0: none)
  double **hist = nullptr;      // the scheme's history per atom (grown with atom->nmax)
  int hist_from_restart = 1;    // 0: a restart file's history is of another scheme: not taken
  // how the forces of the other fixes enter the step (decided in init, choose_external(), by
  // the rule of solvers/external_forces.h): NONE there are none; IMPLICIT all re-evaluated at
  // every iterate; MIXED those that add forces re-evaluated, the others lagged (their force of
  // the evaluation that ended the previous step); LAGGED all lagged
  PeriSISSM::ExternalMode external_mode = PeriSISSM::ExternalMode::none;
  std::vector<class Fix *> implicit_fixes;    // re-evaluated at every iterate, in LAMMPS order
  // contact that makes the step collision-free: every move of the atoms is limited by it
  // (collision_limit.h)
  std::vector<class CollisionLimit *> limiters;
  // contact fixes re-evaluated at every iterate (lagged friction: begin_step), limiting or not
  std::vector<class CollisionLimit *> contacts;
  // contact fixes that adapt their stiffness to the step (kappa auto; among the contacts)
  std::vector<class CollisionLimit *> adapting;
  int balance_first = 0;        // the next evaluation is the first of a (sub-)step: balance them
  int reach_cut = 0;            // the last evaluation's move was cut short by a contact's reach
  std::string external_note;    // what was last logged about them
  double dtv = 0.0;
  double tol_step = 1.0e-6;    // the tolerance of the current step (SissmSystem::step_tolerance())

  // statistics (global vector): the last step's evaluations, measure, sub-steps (1: not cut
  // back), Newton steps and Krylov iterations; the run's steps, evaluations, unconverged steps,
  // steps cut back and steps redone with the other preconditioner (precond amg)
  int last_iterations = 0, last_substeps = 1, last_newton = 0, last_krylov = 0;
  double last_measure = 0.0;
  bigint nsteps_run = 0, iterations_run = 0, unconverged_run = 0, cutback_run = 0, fallback_run = 0;
  int block_first = 0;    // precond amg: the blocks converged the last step that amg did not
  // warnings already given in this run: unconverged, round-off floor, preconditioner switch
  int warned = 0, warned_roundoff = 0, warned_fallback = 0;
  int nmax = 0;
  double **fint = nullptr;       // internal force density at y^n (captured in pre_reverse; lagged,
                                 //   mixed)
  double **fext = nullptr;       // force density of the other fixes at the last evaluation
                                 //   (implicit, mixed: used by the momentum balance; lagged: zero)
  double **flagged = nullptr;    // mixed: force density of the lagged fixes for this step
  double **yn = nullptr;         // y^n of owned atoms
  double **yhat = nullptr;       // predictor y^n + h v^n (+ h^2 f_ext / rho when lagged)
  double **res = nullptr;        // backward-Euler residual of the last evaluation
  double **kblock = nullptr;     // implicit block sum_j omega_ij (H_i + H_j + S_ij) per atom
  double **rprev = nullptr, **dprev = nullptr;    // relax: residual, correction of the last sweep
  double **xbase = nullptr, **rbase = nullptr, **jbase = nullptr, **cres = nullptr,
         **zdir = nullptr, **pdir = nullptr, **sdir = nullptr;    // krylov vectors
  double *term = nullptr;                           // krylov: per-atom terms of a global sum
  double **moment = nullptr;                        // per-atom terms of the momentum balance
  double **xstart = nullptr, **vstart = nullptr;    // cutback: y^n, v^n of the group; end
                                                    //   positions of the others
  double **hstart = nullptr;          // the history at the start of the step (redone steps)
  std::vector<double> state_start;    // the scheme's global state at the start of the step
  double **vn = nullptr, **fstart = nullptr;    // with history: v^n, the force density at y^n
  double *gnode = nullptr;    // amg: global node number of each atom (-1: not an unknown)
  double *psize = nullptr;    // V^(1/3) of each atom (Rows::size), refreshed at every step
  friend class SissmAmg;
  friend class SissmSystem;
  friend class SissmAttempts;

  struct WorkArray;    // (fix_sissm.cpp)
  std::vector<WorkArray> work_arrays();
  void grow();
  void destroy_arrays();
  void choose_external();
  void begin_path(double h);
  void limit_path(bool end_of_step);
  void capture_internal_force();
  void lagged_external_force();
  PeriSISSM::SolveResult solve_step(double h, double t_end, double **flag);
  void place_others(double t);
  void restore_start();
  void report_retries(const PeriSISSM::RetryOutcome &outcome);
  std::unique_ptr<PeriSISSM::Preconditioner> make_amg();
};

}    // namespace LAMMPS_NS

#endif
#endif
