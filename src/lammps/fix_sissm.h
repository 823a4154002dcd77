/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix sissm (doc/fix_sissm.rst), the LAMMPS glue of the core's solvers (src/core/solvers): it
   owns the per-atom storage and runs the step's retry ladder; the nonlinear system the solvers
   see (fix_sissm_system.cpp) is its group's atoms, with the force model behind the
   ImplicitForces interface of the pair style.
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
#include "solvers/newton_krylov.h"
#include "solvers/step_options.h"
#include "solvers/step_report.h"
#include "solvers/step_start.h"
#include "solvers/time_scheme.h"

#include <memory>
#include <string>
#include <vector>

namespace PeriSISSM {
class Preconditioner;
struct CarriedArray;
}    // namespace PeriSISSM

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
  // the Newton steps' forcing term carried from solve to solve (solvers/newton_krylov.h; kept
  // in restart files)
  PeriSISSM::NewtonForcing forcing;
  std::unique_ptr<PeriSISSM::TimeScheme> scheme;    // which implicit step
  PeriSISSM::StepOptions opt;                       // the keywords (solvers/step_options.h)
  PeriSISSM::StepArrays arrays;                     // the per-atom arrays of the step being solved
  int ncols = 0;                // the scheme's per-atom history columns (0: none)
  double **hist = nullptr;      // the scheme's history per atom (grown with atom->nmax)
  int hist_from_restart = 1;    // 0: a restart file's history is of another scheme: not taken
  // how the forces of the other fixes enter the step (solvers/external_forces.h; init)
  PeriSISSM::ExternalMode external_mode = PeriSISSM::ExternalMode::none;
  std::vector<class Fix *> implicit_fixes;    // re-evaluated at every iterate, in LAMMPS order
  // contact fixes (collision_limit.h) re-evaluated at every iterate, and among them those that
  // make the step collision-free (limiting every move) and those that adapt their stiffness
  std::vector<class CollisionLimit *> contacts, limiters, adapting;
  int balance_first = 0;      // the next evaluation is the first of a (sub-)step: balance them
  int reach_cut = 0;          // the last evaluation's move was cut short by a contact's reach
  double reach_kept = 1.0;    // ... to this fraction (the smallest over the contacts that cut it)
  class CollisionLimit *reach_limiter = nullptr;    // ... by this contact's reach (null: none)
  // the contact whose reach cut the last solve's end of step short (null: none)
  class CollisionLimit *end_reach = nullptr;
  std::string external_note;    // what was last logged about them
  double dtv = 0.0;
  double tol_step = 1.0e-6;    // the tolerance of the current step (SissmSystem::step_tolerance())

  PeriSISSM::StepStatistics stats;    // the global vector (solvers/step_report.h)
  // precond amg: the steps left in which the blocks go first, after they converged a step that
  // amg did not (solvers/step_retry.h)
  int block_first = 0;
  // warnings already given in this run: unconverged, round-off floor, preconditioner switch
  int warned = 0, warned_roundoff = 0, warned_fallback = 0;
  int nmax = 0;
  double **fint = nullptr;    // lagged, mixed: the pair's force density at y^n (pre_reverse)
  double **fext = nullptr;    // the other fixes' force density of the last evaluation (lagged: 0)
  double **flagged = nullptr;    // mixed: force density of the lagged fixes for this step
  double **yn = nullptr;         // y^n of owned atoms
  double **yhat = nullptr;       // predictor y^n + h v^n (+ h^2 f_ext / rho when lagged)
  double **res = nullptr;        // backward-Euler residual of the last evaluation
  double **kblock = nullptr;     // implicit block sum_j omega_ij (H_i + H_j + S_ij) per atom
  double **rprev = nullptr, **dprev = nullptr;    // relax: residual, move of the last sweep
  double **yprev = nullptr;    // chebyshev: the iterate the last sweep started from
  double **xbase = nullptr, **rbase = nullptr, **jbase = nullptr, **cres = nullptr,
         **zdir = nullptr, **pdir = nullptr, **sdir = nullptr;    // krylov vectors
  double *term = nullptr;                           // krylov: per-atom terms of a global sum
  double **moment = nullptr;                        // per-atom terms of the momentum balance
  double **xstart = nullptr, **vstart = nullptr;    // redone steps: y^n, v^n (others: end)
  double **hstart = nullptr;          // the history at the start of the step (redone steps)
  std::vector<double> state_start;    // the scheme's global state at the start of the step
  double **vn = nullptr, **fstart = nullptr;    // with history: v^n, the force density at y^n
  // amg: global node number of each atom (-1: not an unknown); it travels with the atom, so a
  // hierarchy outlives atoms changing processes or local slots (fix_sissm_amg.cpp)
  double *gnode = nullptr;
  bool travels = false;       // amg: gnode is allocated and travels
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
  PeriSISSM::StepStart step_start() const { return {xstart, vstart, hstart, ncols}; }
  void report_retries(const PeriSISSM::RetryOutcome &outcome);
  PeriSISSM::StepContext context() const;    // what the log's texts say about the step
  std::unique_ptr<PeriSISSM::Preconditioner> make_amg();
  // neighbor list builds inside a cut-back step (fix_sissm_neighbor.cpp)
  void start_substep();
  bool beyond_reach();
  std::vector<PeriSISSM::CarriedArray> carried_arrays();
  void build_neighbors_in_step();
};

}    // namespace LAMMPS_NS

#endif
#endif
