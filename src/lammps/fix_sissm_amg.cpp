/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm precond amg (doc/fix_sissm.rst, "Preconditioners"; doc/theory.rst,
   "The coarse level").

   At every Newton step the preconditioning matrix
     M = V (rho I + c P),   c the time scheme's force factor (h^2 for backward Euler),
   P the bond-projected stiffness of the current configuration plus the Gauss-Newton Hessian
   of the membranes' bending hinges (core peri/bond_stiffness.h), is assembled over the
   group's atoms (the unknowns; bonds to atoms outside the group add
   their diagonal part only, as Dirichlet rows eliminated), and z = M^-1 V r is one
   application of PETSc's preconditioner (smoothed-aggregation AMG, PCGAMG, with the six
   rigid-body modes of the current positions as near-null space). J itself stays matrix-free.
   The owned unknowns are numbered contiguously in rank order and the numbers reach the ghosts
   by a forward communication. A row's columns are its unbroken bonds' partners, then the
   other vertices of its hinges that are not bond partners. The sparsity pattern is built
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

#include "peri/bond_stiffness.h"
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

#include <algorithm>
#include <stdexcept>

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
  std::vector<int> first_, partner_;    // the springs the pattern was built for
  std::vector<int> hinge_vertex_;       // and the hinges
  // the pattern's blocks row by row (owned unknowns in order): row r holds blocks
  // row_first_[r] .. row_first_[r+1]-1, the diagonal first, with global columns col_
  std::vector<int> row_first_, col_, rows_;
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
  bool build_pattern();
  // the block (row r, global column gcol) in values_ (-1: not in the pattern)
  int find_block(int r, int gcol) const;
  // the hinges of each owned atom: hinge_of_[hinge_first_[i] .. hinge_first_[i+1]-1] holds
  // 4 h + v for its place v in hinge h
  std::vector<int> hinge_first_, hinge_of_;
  void index_hinges(int nlocal);
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

bool SissmAmg::build_pattern()
{
  Atom *atom = fix_->atom;
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const int *mask = atom->mask;
  const int bit = fix_->groupbit;
  double *gnode = fix_->gnode;
  int count = 0;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & bit) count++;
  int offset = 0;
  MPI_Exscan(&count, &offset, 1, MPI_INT, MPI_SUM, fix_->world);
  if (fix_->comm->me == 0) offset = 0;
  int next = offset;
  for (int i = 0; i < nall; i++) gnode[i] = -1.0;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & bit) gnode[i] = next++;
  fix_->comm->forward_comm(fix_);

  std::vector<int> &rows = rows_;
  std::vector<int> old_first, old_col;
  rows.clear();
  row_first_.swap(old_first);
  col_.swap(old_col);
  row_first_.assign(1, 0);
  col_.clear();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & bit)) continue;
    const int gi = (int) gnode[i];
    const int r = (int) row_first_.size() - 1;
    col_.push_back(gi);
    for (int s = springs_.first[i]; s < springs_.first[i + 1]; s++) {
      const int gj = (int) gnode[springs_.partner[s]];
      if (gj >= 0) col_.push_back(gj);
    }
    for (int q = hinge_first_[i]; q < hinge_first_[i + 1]; q++) {
      const int *v = &hinges_.vertex[4 * (hinge_of_[q] / 4)];
      for (int b = 0; b < 4; b++) {
        const int gj = (int) gnode[v[b]];
        if (gj < 0) continue;
        col_.push_back(gj);    // provisionally, to find it below
        if (find_block(r, gj) != (int) col_.size() - 1) col_.pop_back();
      }
    }
    row_first_.push_back((int) col_.size());
    rows.resize(col_.size(), gi);
  }
  first_ = springs_.first;
  partner_ = springs_.partner;
  hinge_vertex_ = hinges_.vertex;
  built_at_ = fix_->neighbor->lastcall;
  nlocal_ = nlocal;
  int same = amg_ && count == nodes_ && row_first_ == old_first && col_ == old_col;
  int all = 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, fix_->world);
  if (all) return false;

  nodes_ = count;
  values_.assign(9 * rows.size(), 0.0);
  coords_.assign(3 * count, 0.0);
  b_.assign(3 * count, 0.0);
  z_.assign(3 * count, 0.0);
  try {
    if (!amg_)
      amg_ = std::make_unique<PetscAmg>(fix_->world, fmt::format("sissm_{}_", fix_->id),
                                        fix_->petsc_options);
  } catch (std::runtime_error &e) {
    fail(e);
  }
  make_hierarchy();
  return true;
}

void SissmAmg::make_hierarchy()
{
  try {
    amg_->set_pattern(nodes_, rows_, col_);
  } catch (std::runtime_error &e) {
    fail(e);
  }
  patterns_++;
  interp_at_ = built_at_;
  reinterp_ = false;
  fresh_interp_ = true;
}

// (row r may be the one being built: its blocks then run to the end of col_)
int SissmAmg::find_block(int r, int gcol) const
{
  const int end = r + 1 < (int) row_first_.size() ? row_first_[r + 1] : (int) col_.size();
  for (int m = row_first_[r]; m < end; m++)
    if (col_[m] == gcol) return m;
  return -1;
}

void SissmAmg::index_hinges(int nlocal)
{
  hinge_first_.assign(nlocal + 1, 0);
  const int nh = hinges_.count();
  for (int h = 0; h < nh; h++)
    for (int v = 0; v < 4; v++) {
      const int i = hinges_.row[4 * h + v];
      if (i >= 0) hinge_first_[i + 1]++;
    }
  for (int i = 0; i < nlocal; i++) hinge_first_[i + 1] += hinge_first_[i];
  hinge_of_.resize(hinge_first_[nlocal]);
  std::vector<int> next(hinge_first_.begin(), hinge_first_.end() - 1);
  for (int h = 0; h < nh; h++)
    for (int v = 0; v < 4; v++) {
      const int i = hinges_.row[4 * h + v];
      if (i >= 0) hinge_of_[next[i]++] = 4 * h + v;
    }
}

void SissmAmg::prepare(PeriSISSM::NonlinearSystem &)
{
  Atom *atom = fix_->atom;
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const int bit = fix_->groupbit;
  double **x = atom->x;
  const double *rho = atom->rmass, *vol = atom->vfrac;
  const double c = fix_->scheme->force_factor();
  fix_->forces->bond_springs(springs_);
  // (the hinges' gradients only when the matrix is assembled: most Newton steps keep it)
  fix_->forces->hinge_couplings(hinges_, false);
  index_hinges(nlocal);
  const bool same_pattern = pattern_current() || !build_pattern();
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

  const double *gnode = fix_->gnode;
  std::fill(values_.begin(), values_.end(), 0.0);
  int node = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & bit)) continue;
    const int r = node;
    int m = row_first_[r];
    double *diag = &values_[9 * m++];
    for (int k = 0; k < 9; k += 4) diag[k] = vol[i] * rho[i];
    for (int s = springs_.first[i]; s < springs_.first[i + 1]; s++) {
      const double *e = &springs_.e[3 * s];
      const double ck = c * springs_.k[s];
      const bool unknown = gnode[springs_.partner[s]] >= 0.0;
      double *off = unknown ? &values_[9 * m++] : nullptr;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          const double kab = ck * e[a] * e[b];
          diag[3 * a + b] += kab;
          if (off) off[3 * a + b] -= kab;
        }
    }
    // the hinges: row v of c g g^T, blocks g_v g_b^T (g = sqrt(2 c_hinge) grad theta)
    for (int q = hinge_first_[i]; q < hinge_first_[i + 1]; q++) {
      const int h = hinge_of_[q] / 4, v = hinge_of_[q] % 4;
      const double *g = &hinges_.grad[12 * h];
      for (int b = 0; b < 4; b++) {
        const int j = hinges_.vertex[4 * h + b];
        const int gj = b == v ? (int) gnode[i] : (int) gnode[j];
        if (gj < 0) continue;    // outside the group: held, no column
        double *blk = &values_[9 * find_block(r, gj)];
        for (int a = 0; a < 3; a++)
          for (int d = 0; d < 3; d++) blk[3 * a + d] += c * g[3 * v + a] * g[3 * b + d];
      }
    }
    for (int k = 0; k < 3; k++) coords_[3 * node + k] = x[i][k];
    node++;
  }
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
  const PeriSISSM::Rows &rows = sys.rows();
  int node = 0;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int k = 0; k < 3; k++) b_[3 * node + k] = rows.volume[i] * r[i][k];
    node++;
  }
  try {
    amg_->apply(b_.data(), z_.data());
  } catch (std::runtime_error &e) {
    fail(e);
  }
  node = 0;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int k = 0; k < 3; k++) z[i][k] = z_[3 * node + k];
    node++;
  }
}

#else

std::unique_ptr<PeriSISSM::Preconditioner> FixSissm::make_amg()
{
  return nullptr;    // refused in the constructor
}

#endif
