/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm precond amg (doc/fix_sissm.rst, "Preconditioners"; doc/theory.rst,
   "The coarse level").

   At every Newton step the preconditioning matrix M of solvers/block_matrix.h is assembled
   over the group's atoms (the unknowns), and z = M^-1 V r is one application of PETSc's
   preconditioner (smoothed-aggregation AMG, PCGAMG, with the six rigid-body modes of the current
   positions as near-null space). J itself stays matrix-free.
   The owned unknowns are numbered contiguously in rank order and the numbers reach the ghosts
   by a forward communication. The sparsity pattern is built
   again after a neighbor list build or when the owned atoms, their unbroken bonds or their
   hinges changed, and the hierarchy is kept when that pattern is the old one (atoms that
   neither migrated nor were sorted: measured, a falling cloth of 33K vertices set it up 7
   times in 30 steps before, after every build).
   A set-up costs tens of force evaluations and one application one or two, so the hierarchy is
   kept across Newton steps and time steps while it works: it is set up again (reusing its
   interpolation when the pattern is unchanged) when the pattern or the time step changed, when
   a step did not converge, or when a step needed more than 1.5x (+2) the Krylov iterations per
   Newton step of the first step that used it. Which M is used changes the iterations, not the
   converged answer.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "implicit_forces.h"

#include "solvers/block_matrix.h"
#include "solvers/preconditioner.h"
#include "solvers/time_scheme.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "neighbor.h"
#include "update.h"

#ifdef PERISISSM_HAVE_PETSC
#include "petsc_amg.h"
#endif

#include <stdexcept>
#include <utility>

using namespace LAMMPS_NS;

#ifdef PERISISSM_HAVE_PETSC

namespace LAMMPS_NS {

class SissmAmg : public PeriSISSM::Preconditioner {
 public:
  SissmAmg(FixSissm *fix) : fix_(fix) {}
  void prepare(PeriSISSM::NonlinearSystem &sys) override;
  void apply(PeriSISSM::NonlinearSystem &sys, double **r, double **z) override;
  void finished(int newton, int krylov, bool converged) override;
  bool refresh() override;
  std::string summary() const override;

 private:
  FixSissm *fix_;
  std::unique_ptr<PetscAmg> amg_;
  PeriSISSM::BondSprings springs_;
  PeriSISSM::HingeCouplings hinges_;
  PeriSISSM::HingeIndex hinge_index_;
  PeriSISSM::BlockPattern pattern_;     // the blocks of the owned unknowns (solvers/block_matrix.h)
  std::vector<int> first_, partner_;    // the springs the pattern was built for
  std::vector<int> hinge_vertex_;       // and the hinges
  bigint interp_at_ = -1;    // neighbor->lastcall when the hierarchy's interpolation was made
  bool reinterp_ = false;    // the next set-up makes a new interpolation (a step failed)
  bigint built_at_ = -1;     // neighbor->lastcall of that build
  int nlocal_ = -1;
  int nodes_ = 0;
  bool logged_ = false;
  bool stale_ = true;            // set up again at the next prepare()
  int solves_ = 0;               // solves that used the current set-up
  bool used_ = false;            // the solve under way applied the hierarchy
  bool fresh_ = false;           // and set it up
  bool fresh_interp_ = false;    // and made its aggregates and interpolation
  bool lagged_ = false;          // the last solve used a hierarchy (or its interpolation) made
                                 //   in an earlier one
  bigint setups_ = 0, patterns_ = 0;    // set-ups so far, and those that made a new PETSc PC
  double set_factor_ = 0.0;             // the time scheme's force factor at the last set-up
  double baseline_ = 0.0;               // Krylov iterations per Newton step of its first solve
  std::vector<double> values_, coords_, b_, z_;
  bool pattern_current();
  // numbers the unknowns and builds the pattern; false (all ranks) when it is the one the
  // hierarchy has already (a neighbor list build that moved no atom between slots or ranks)
  bool build_pattern(const PeriSISSM::Rows &rows);
  // a new PETSc hierarchy (aggregates and interpolation) for the current pattern
  void make_hierarchy();
  void fail(const std::runtime_error &e);
};

}    // namespace LAMMPS_NS

std::unique_ptr<PeriSISSM::Preconditioner> FixSissm::make_amg()
{
  return std::make_unique<SissmAmg>(this);
}

void SissmAmg::fail(const std::runtime_error &e)
{
  fix_->error->one(FLERR, "Fix sissm {} precond amg: {}", fix_->id, e.what());
}

// true on all ranks when no rank's pattern can have changed
bool SissmAmg::pattern_current()
{
  Atom *atom = fix_->atom;
  int same = amg_ && built_at_ == fix_->neighbor->lastcall && nlocal_ == atom->nlocal &&
      first_ == springs_.first && partner_ == springs_.partner && hinge_vertex_ == hinges_.vertex;
  int all = 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, fix_->world);
  return all == 1;
}

bool SissmAmg::build_pattern(const PeriSISSM::Rows &rows)
{
  Atom *atom = fix_->atom;
  double *gnode = fix_->gnode;
  int count = 0;
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i)) count++;
  int offset = 0;
  MPI_Exscan(&count, &offset, 1, MPI_INT, MPI_SUM, fix_->world);
  if (fix_->comm->me == 0) offset = 0;
  for (int i = 0; i < atom->nlocal + atom->nghost; i++) gnode[i] = -1.0;
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i)) gnode[i] = offset++;
  fix_->comm->forward_comm(fix_);

  const PeriSISSM::BlockPattern old = std::move(pattern_);
  PeriSISSM::build_block_pattern(rows, gnode, springs_, hinges_, hinge_index_, pattern_);
  first_ = springs_.first;
  partner_ = springs_.partner;
  hinge_vertex_ = hinges_.vertex;
  built_at_ = fix_->neighbor->lastcall;
  nlocal_ = atom->nlocal;
  int same = amg_ && count == nodes_ && pattern_ == old;
  int all = 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, fix_->world);
  if (all) return false;

  nodes_ = count;
  z_.assign(3 * count, 0.0);
  try {
    if (!amg_)
      amg_ = std::make_unique<PetscAmg>(fix_->world, fmt::format("sissm_{}_", fix_->id),
                                        fix_->opt.petsc);
  } catch (std::runtime_error &e) {
    fail(e);
  }
  make_hierarchy();
  return true;
}

void SissmAmg::make_hierarchy()
{
  try {
    amg_->set_pattern(nodes_, pattern_.row, pattern_.col);
  } catch (std::runtime_error &e) {
    fail(e);
  }
  patterns_++;
  interp_at_ = built_at_;
  reinterp_ = false;
  fresh_interp_ = true;
}

void SissmAmg::prepare(PeriSISSM::NonlinearSystem &sys)
{
  const PeriSISSM::Rows &rows = sys.rows();
  const double c = fix_->scheme->force_factor();
  fix_->forces->bond_springs(springs_);
  // (the hinges' gradients only when the matrix is assembled: most Newton steps keep it)
  fix_->forces->hinge_couplings(hinges_, false);
  PeriSISSM::index_hinges(hinges_, rows.n, hinge_index_);
  const bool same_pattern = pattern_current() || !build_pattern(rows);
  used_ = true;
  if (same_pattern && !stale_ && set_factor_ == c) return;
  fix_->forces->hinge_couplings(hinges_, true);
  fresh_ = true;
  stale_ = false;
  // an interpolation is only as good as the rigid-body modes and the matrix it was made from:
  // a new one once the atoms moved far enough for a neighbor list build, and after a failed
  // step (measured: a cloth falling from flat, the first step's interpolation kept to step 23,
  // failed that step with values set up in it; a new interpolation converged it)
  if (same_pattern && (reinterp_ || interp_at_ != built_at_)) make_hierarchy();
  solves_ = 0;
  setups_++;
  set_factor_ = c;
  PeriSISSM::assemble_blocks(rows, fix_->gnode, c, springs_, hinges_, hinge_index_, pattern_,
                             fix_->atom->x, values_, coords_);
  try {
    amg_->set_values(values_, coords_.data());
  } catch (std::runtime_error &e) {
    fail(e);
  }
  if (!logged_) {
    // describe() is collective (the matrix's global nonzero count): every rank calls it
    const std::string what = amg_->describe();
    if (fix_->comm->me == 0)
      utils::logmesg(fix_->lmp, "Fix sissm {} precond amg: {}\n", fix_->id, what);
    logged_ = true;
  }
}

// the counts are global (every rank decides the same)
void SissmAmg::finished(int newton, int krylov, bool converged)
{
  lagged_ = used_ && !(fresh_ && fresh_interp_);
  if (used_) {
    const double rate = (double) krylov / (newton > 0 ? newton : 1);
    // (a hierarchy that has grown this much worse was made for another configuration: its
    // interpolation too)
    if (solves_++ == 0)
      baseline_ = rate;
    else if (rate > 1.5 * baseline_ + 2.0)
      stale_ = reinterp_ = true;
    if (!converged) stale_ = true;
  }
  used_ = fresh_ = fresh_interp_ = false;
}

std::string SissmAmg::summary() const
{
  return fmt::format("{} set-up{} of the AMG hierarchy ({} with new aggregates and "
                     "interpolation)",
                     setups_, setups_ == 1 ? "" : "s", patterns_);
}

// (a solve that never reached a Newton step did not use the hierarchy: nothing to refresh)
bool SissmAmg::refresh()
{
  stale_ = true;
  reinterp_ = true;
  return lagged_;
}

void SissmAmg::apply(PeriSISSM::NonlinearSystem &sys, double **r, double **z)
{
  PeriSISSM::gather_weighted(sys.rows(), r, b_);
  try {
    amg_->apply(b_.data(), z_.data());
  } catch (std::runtime_error &e) {
    fail(e);
  }
  PeriSISSM::scatter_unknowns(sys.rows(), z_, z);
}

#else

std::unique_ptr<PeriSISSM::Preconditioner> FixSissm::make_amg()
{
  return nullptr;    // refused in the constructor
}

#endif
