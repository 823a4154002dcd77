/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm precond amg (doc/fix_sissm.rst, "Preconditioners": what is assembled,
   and when the pattern, the hierarchy and its interpolation are made again). The matrix of
   solvers/block_matrix.h over the group's atoms, numbered contiguously in rank order when a
   hierarchy is made (the numbers travel with the atoms and reach the ghosts by a forward
   communication), applied by PETSc (petsc_amg.h).
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

#include <cstdint>
#include <stdexcept>
#include <utility>

using namespace LAMMPS_NS;

#ifdef PERISISSM_HAVE_PETSC

namespace LAMMPS_NS {

// PETSc options for a group of membrane particles only, before the user's: the interpolation of
// the plain aggregates, not smoothed (measured on the hanging cloth: the same CG iterations
// for about 16% less CPU time; on the solid cantilever's static step smoothing is needed)
constexpr const char *kMembraneOptions = "-pc_gamg_agg_nsmooths 0";

// the share of the unknowns that may sit on other ranks than their PETSc rows before a set-up
// numbers them again (their values and vector entries then travel at every set-up and
// application)
constexpr double kMovedRows = 0.1;

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
  PeriSISSM::CouplingIndex hinge_index_;
  PeriSISSM::PlateCouplings plates_;
  PeriSISSM::CouplingIndex plate_index_;
  PeriSISSM::BlockPattern pattern_;     // the blocks of the owned unknowns (solvers/block_matrix.h)
  std::vector<int> first_, partner_;    // the springs the pattern was built for
  std::vector<int> hinge_vertex_;       // and the hinges
  std::vector<int> plate_first_;        // and the plate stencils
  std::vector<int> plate_vertex_;
  bigint built_at_ = -1;                // neighbor->lastcall of that build
  int nlocal_ = -1;
  bigint total_ = 0;                    // unknowns of all ranks when they were numbered
  int numbered_from_ = 0, numbered_ = 0;    // this rank's numbers then: [from, from + count)
  std::uint64_t signature_ = 0;         // the pattern's (all ranks)
  std::uint64_t matrix_signature_ = 0;    // the pattern PETSc's matrix was made with
  std::vector<std::uint64_t> matrix_blocks_;    // and this rank's blocks of it (sorted keys)
  bool logged_ = false;
  bool cost_pending_ = false;    // a set-up whose cost the next application tells
  bool values_only_ = false;     // it kept the interpolation
  std::vector<double> values_, coords_, b_, z_;
  std::vector<int> unknown_nodes_;
  bool all_ranks(bool mine);
  bool pattern_current();
  // the pattern of the current atoms; false (all ranks) when PETSc's matrix holds it: the
  // unknowns still carry the numbers they were given and are coupled as they were, or by fewer
  // of the same blocks (bonds broke; their blocks stay in the matrix as zeros)
  bool build_pattern(const PeriSISSM::Rows &rows);
  // the unknowns numbered contiguously in rank order, and their pattern
  void number_unknowns(const PeriSISSM::Rows &rows);
  // the pattern and its signature from the unknowns' numbers (their ghosts' too)
  void pattern_from_numbers(const PeriSISSM::Rows &rows);
  // whether every unknown of this rank carries a number and no other atom does
  bool numbers_carried(const PeriSISSM::Rows &rows) const;
  // a new PETSc matrix and hierarchy (aggregates and interpolation) for the current pattern
  void make_hierarchy();
  // whether more than kMovedRows of the unknowns (all ranks) are on another rank than the one
  // that numbered them (whose PETSc rows they are): numbered again with the next set-up
  bool rows_moved();
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
                   hinge_vertex_ == hinges_.vertex && plate_first_ == plates_.first &&
                   plate_vertex_ == plates_.vertex);
}

bool SissmAmg::numbers_carried(const PeriSISSM::Rows &rows) const
{
  for (int i = 0; i < rows.n; i++)
    if ((fix_->gnode[i] >= 0.0) != rows.has(i)) return false;
  return true;
}

void SissmAmg::pattern_from_numbers(const PeriSISSM::Rows &rows)
{
  fix_->comm->forward_comm(fix_);
  PeriSISSM::build_block_pattern(rows, fix_->gnode, springs_, hinges_, hinge_index_, plates_,
                                 plate_index_, pattern_);
  std::uint64_t mine = PeriSISSM::pattern_signature(pattern_);
  MPI_Allreduce(&mine, &signature_, 1, MPI_UINT64_T, MPI_SUM, fix_->world);
  first_ = springs_.first;
  partner_ = springs_.partner;
  hinge_vertex_ = hinges_.vertex;
  plate_first_ = plates_.first;
  plate_vertex_ = plates_.vertex;
  built_at_ = fix_->neighbor->lastcall;
  nlocal_ = fix_->atom->nlocal;
  unknown_nodes_.clear();
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i)) unknown_nodes_.push_back((int) fix_->gnode[i]);
}

void SissmAmg::number_unknowns(const PeriSISSM::Rows &rows)
{
  Atom *atom = fix_->atom;
  const int count = PeriSISSM::count_unknowns(rows);
  int offset = 0;
  MPI_Exscan(&count, &offset, 1, MPI_INT, MPI_SUM, fix_->world);
  if (fix_->comm->me == 0) offset = 0;
  PeriSISSM::number_unknowns(rows, offset, atom->nlocal + atom->nghost, fix_->gnode);
  numbered_from_ = offset;
  numbered_ = count;
  bigint mine = count;
  MPI_Allreduce(&mine, &total_, 1, MPI_LMP_BIGINT, MPI_SUM, fix_->world);
  pattern_from_numbers(rows);
}

bool SissmAmg::build_pattern(const PeriSISSM::Rows &rows)
{
  // the numbers travel with the atoms (fix_sissm_history.cpp): while every unknown carries its
  // own and the couplings are the same, PETSc's matrix and hierarchy stay
  bigint count = PeriSISSM::count_unknowns(rows), all = 0;
  MPI_Allreduce(&count, &all, 1, MPI_LMP_BIGINT, MPI_SUM, fix_->world);
  if (amg_ && all == total_ && all_ranks(numbers_carried(rows))) {
    pattern_from_numbers(rows);
    // (bonds that broke leave fewer blocks: their values lag until the next set-up, which the
    // Krylov iterations ask for when they grow)
    if (signature_ == matrix_signature_ ||
        all_ranks(PeriSISSM::pattern_within(pattern_, matrix_blocks_))) {
      guarded([&] {
        amg_->set_unknowns(unknown_nodes_);
      });
      return false;
    }
  }
  number_unknowns(rows);
  if (!amg_) {
    // membranes: plain aggregates, unless the plate energy's own couplings are in the matrix
    // (a static step of a bending plate); decided at the first set-up (doc/fix_sissm.rst,
    // "PETSc options"), before the user's options
    const bool plain =
        fix_->forces->only_membranes(fix_->groupbit) && all_ranks(plates_.count() == 0);
    const std::string options =
        (plain ? std::string(kMembraneOptions) + " " : std::string()) + fix_->opt.petsc;
    guarded([&] {
      amg_ = std::make_unique<PetscAmg>(fix_->world, fmt::format("sissm_{}_", fix_->id), options);
    });
  }
  make_hierarchy();
  return true;
}

bool SissmAmg::rows_moved()
{
  bigint away = 0, all = 0;
  for (int node : unknown_nodes_)
    if (node < numbered_from_ || node >= numbered_from_ + numbered_) away++;
  MPI_Allreduce(&away, &all, 1, MPI_LMP_BIGINT, MPI_SUM, fix_->world);
  return all > kMovedRows * total_;
}

void SissmAmg::make_hierarchy()
{
  guarded([&] {
    amg_->set_pattern((int) unknown_nodes_.size(), pattern_.row, pattern_.col);
    amg_->set_unknowns(unknown_nodes_);
  });
  matrix_signature_ = signature_;
  matrix_blocks_ = PeriSISSM::pattern_blocks(pattern_);
  schedule_.made_hierarchy();
}

void SissmAmg::prepare(PeriSISSM::NonlinearSystem &sys)
{
  const PeriSISSM::Rows &rows = sys.rows();
  const double c = fix_->scheme->force_factor();
  // (the springs' values and the hinges' gradients only when the matrix is assembled: most
  // Newton steps keep it)
  fix_->forces->bond_springs(springs_, false);
  fix_->forces->hinge_couplings(hinges_, false);
  PeriSISSM::index_couplings(hinges_.row, rows.n, hinge_index_);
  // (constant Hessians, made with the pair's list)
  PeriSISSM::significant_plates(fix_->forces->plate_couplings(), rows, c,
                                PeriSISSM::kPlateSignificance, plates_);
  PeriSISSM::index_couplings(plates_.row, rows.n, plate_index_);
  const bool same_pattern = pattern_current() || !build_pattern(rows);
  if (!schedule_.setup_wanted(same_pattern, c)) return;
  fix_->forces->bond_springs(springs_, true);
  fix_->forces->hinge_couplings(hinges_, true);
  values_only_ = same_pattern;
  if (schedule_.begin_setup(same_pattern, rows_moved(), c)) {
    // (numbered again: the matrix's rows go back to the processes of their atoms)
    number_unknowns(rows);
    make_hierarchy();
    values_only_ = false;
  }
  cost_pending_ = true;
  PeriSISSM::assemble_blocks(rows, fix_->gnode, c, springs_, hinges_, hinge_index_, plates_,
                             plate_index_, pattern_, fix_->atom->x, values_, coords_);
  guarded([&] {
    amg_->set_values(pattern_.row, pattern_.col, values_, coords_.data());
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
  z_.resize(b_.size());
  guarded([&] {
    amg_->apply(b_.data(), z_.data());
  });
  if (cost_pending_) schedule_.measured_setup(amg_->setup_in_applications(), values_only_);
  cost_pending_ = false;
  PeriSISSM::scatter_unknowns(sys.rows(), z_, z);
}

#else

std::unique_ptr<PeriSISSM::Preconditioner> FixSissm::make_amg()
{
  return nullptr;    // refused in the constructor
}

#endif
