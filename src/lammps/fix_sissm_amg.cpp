/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm precond amg (doc/fix_sissm.rst, "Preconditioners": what is assembled,
   and when the pattern, the hierarchy and its interpolation are made again). The matrix of
   solvers/block_matrix.h over the group's atoms, numbered contiguously in rank order (the
   numbers reach the ghosts by a forward communication), applied by PETSc (petsc_amg.h).
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "implicit_forces.h"

#include "solvers/amg_schedule.h"
#include "solvers/block_matrix.h"
#include "solvers/preconditioner.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "neighbor.h"

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
  void finished(int newton, int krylov, bool converged) override
  {
    schedule_.finished(newton, krylov, converged);
  }
  bool refresh() override { return schedule_.refresh(); }
  std::string summary() const override { return schedule_.summary(); }
  bool estimates_error() const override { return true; }

 private:
  FixSissm *fix_;
  std::unique_ptr<PetscAmg> amg_;
  PeriSISSM::AmgSchedule schedule_;    // when the hierarchy is set up again
  PeriSISSM::BondSprings springs_;
  PeriSISSM::HingeCouplings hinges_;
  PeriSISSM::HingeIndex hinge_index_;
  PeriSISSM::BlockPattern pattern_;     // the blocks of the owned unknowns (solvers/block_matrix.h)
  std::vector<int> first_, partner_;    // the springs the pattern was built for
  std::vector<int> hinge_vertex_;       // and the hinges
  bigint built_at_ = -1;                // neighbor->lastcall of that build
  int nlocal_ = -1;
  int nodes_ = 0;
  bool logged_ = false;
  std::vector<double> values_, coords_, b_, z_;
  bool all_ranks(bool mine);
  bool pattern_current();
  // numbers the unknowns and builds the pattern; false (all ranks) when it is the one the
  // hierarchy has already (a neighbor list build that moved no atom between slots or ranks)
  bool build_pattern(const PeriSISSM::Rows &rows);
  // a new PETSc hierarchy (aggregates and interpolation) for the current pattern
  void make_hierarchy();
  // a call of PETSc whose failure ends the run with its message
  template <class Call> void guarded(Call call)
  {
    try {
      call();
    } catch (std::runtime_error &e) {
      fix_->error->one(FLERR, "Fix sissm {} precond amg: {}", fix_->id, e.what());
    }
  }
};

}    // namespace LAMMPS_NS

std::unique_ptr<PeriSISSM::Preconditioner> FixSissm::make_amg()
{
  return std::make_unique<SissmAmg>(this);
}

bool SissmAmg::all_ranks(bool mine)
{
  int one = mine ? 1 : 0, all = 0;
  MPI_Allreduce(&one, &all, 1, MPI_INT, MPI_MIN, fix_->world);
  return all == 1;
}

// true on all ranks when no rank's pattern can have changed
bool SissmAmg::pattern_current()
{
  return all_ranks(amg_ && built_at_ == fix_->neighbor->lastcall && nlocal_ == fix_->atom->nlocal &&
                   first_ == springs_.first && partner_ == springs_.partner &&
                   hinge_vertex_ == hinges_.vertex);
}

bool SissmAmg::build_pattern(const PeriSISSM::Rows &rows)
{
  Atom *atom = fix_->atom;
  double *gnode = fix_->gnode;
  const int count = PeriSISSM::count_unknowns(rows);
  int offset = 0;
  MPI_Exscan(&count, &offset, 1, MPI_INT, MPI_SUM, fix_->world);
  if (fix_->comm->me == 0) offset = 0;
  PeriSISSM::number_unknowns(rows, offset, atom->nlocal + atom->nghost, gnode);
  fix_->comm->forward_comm(fix_);

  const PeriSISSM::BlockPattern old = std::move(pattern_);
  PeriSISSM::build_block_pattern(rows, gnode, springs_, hinges_, hinge_index_, pattern_);
  first_ = springs_.first;
  partner_ = springs_.partner;
  hinge_vertex_ = hinges_.vertex;
  built_at_ = fix_->neighbor->lastcall;
  nlocal_ = atom->nlocal;
  if (all_ranks(amg_ && count == nodes_ && pattern_ == old)) return false;

  nodes_ = count;
  z_.assign(3 * count, 0.0);
  guarded([&] {
    if (!amg_)
      amg_ = std::make_unique<PetscAmg>(fix_->world, fmt::format("sissm_{}_", fix_->id),
                                        fix_->opt.petsc);
  });
  make_hierarchy();
  return true;
}

void SissmAmg::make_hierarchy()
{
  guarded([&] {
    amg_->set_pattern(nodes_, pattern_.row, pattern_.col);
  });
  schedule_.made_hierarchy(built_at_);
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
  if (!schedule_.setup_wanted(same_pattern, c)) return;
  fix_->forces->hinge_couplings(hinges_, true);
  if (schedule_.begin_setup(same_pattern, built_at_, c)) make_hierarchy();
  PeriSISSM::assemble_blocks(rows, fix_->gnode, c, springs_, hinges_, hinge_index_, pattern_,
                             fix_->atom->x, values_, coords_);
  guarded([&] {
    amg_->set_values(values_, coords_.data());
  });
  if (!logged_) {
    // describe() is collective (the matrix's global nonzero count): every rank calls it
    const std::string what = amg_->describe();
    if (fix_->comm->me == 0)
      utils::logmesg(fix_->lmp, "Fix sissm {} precond amg: {}\n", fix_->id, what);
    logged_ = true;
  }
}

void SissmAmg::apply(PeriSISSM::NonlinearSystem &sys, double **r, double **z)
{
  PeriSISSM::gather_weighted(sys.rows(), r, b_);
  guarded([&] {
    amg_->apply(b_.data(), z_.data());
  });
  PeriSISSM::scatter_unknowns(sys.rows(), z_, z);
}

#else

std::unique_ptr<PeriSISSM::Preconditioner> FixSissm::make_amg()
{
  return nullptr;    // refused in the constructor
}

#endif
