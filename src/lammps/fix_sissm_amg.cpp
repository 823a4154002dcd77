/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm precond amg (doc/fix_sissm.rst, "Preconditioners"; doc/theory.rst,
   "The coarse level").

   At every Newton step the preconditioning matrix
     M = V (rho I + c P),   c the time scheme's force factor (h^2 for backward Euler),
   P the bond-projected stiffness of the current configuration (core peri/bond_stiffness.h),
   is assembled over the group's atoms (the unknowns; bonds to atoms outside the group add
   their diagonal part only, as Dirichlet rows eliminated), and z = M^-1 V r is one
   application of PETSc's preconditioner (smoothed-aggregation AMG, PCGAMG, with the six
   rigid-body modes of the current positions as near-null space). J itself stays matrix-free.
   The owned unknowns are numbered contiguously in rank order and the numbers reach the ghosts
   by a forward communication. The sparsity pattern is built again only when it can have
   changed (a neighbor list build: atoms migrated or were sorted; the owned atoms or their
   unbroken bonds changed).
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
  std::vector<int> first_, partner_;    // the springs the pattern was built for
  bigint built_at_ = -1;                // neighbor->lastcall of that build
  int nlocal_ = -1;
  int nodes_ = 0;
  bool logged_ = false;
  bool stale_ = true;          // set up again at the next prepare()
  int solves_ = 0;             // solves that used the current set-up
  bool used_ = false;          // the solve under way applied the hierarchy
  bool fresh_ = false;         // and set it up
  bool lagged_ = false;        // the last solve used a hierarchy set up in an earlier one
  bigint setups_ = 0, patterns_ = 0;    // set-ups and pattern builds so far
  double set_factor_ = 0.0;    // the time scheme's force factor at the last set-up
  double baseline_ = 0.0;      // Krylov iterations per Newton step of its first solve
  std::vector<double> values_, coords_, b_, z_;
  bool pattern_current();
  void build_pattern();
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
      first_ == springs_.first && partner_ == springs_.partner;
  int all = 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, fix_->world);
  return all == 1;
}

void SissmAmg::build_pattern()
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

  std::vector<int> rows, cols;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & bit)) continue;
    const int gi = (int) gnode[i];
    rows.push_back(gi);
    cols.push_back(gi);
    for (int s = springs_.first[i]; s < springs_.first[i + 1]; s++) {
      const int gj = (int) gnode[springs_.partner[s]];
      if (gj < 0) continue;
      rows.push_back(gi);
      cols.push_back(gj);
    }
  }
  nodes_ = count;
  values_.assign(9 * rows.size(), 0.0);
  coords_.assign(3 * count, 0.0);
  b_.assign(3 * count, 0.0);
  z_.assign(3 * count, 0.0);
  try {
    if (!amg_)
      amg_ = std::make_unique<PetscAmg>(fix_->world, fmt::format("sissm_{}_", fix_->id),
                                        fix_->petsc_options);
    amg_->set_pattern(count, rows, cols);
  } catch (std::runtime_error &e) {
    fail(e);
  }
  patterns_++;
  first_ = springs_.first;
  partner_ = springs_.partner;
  built_at_ = fix_->neighbor->lastcall;
  nlocal_ = nlocal;
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
  const bool same_pattern = pattern_current();
  used_ = true;
  if (same_pattern && !stale_ && set_factor_ == c) return;
  fresh_ = true;
  if (!same_pattern) build_pattern();
  stale_ = false;
  solves_ = 0;
  setups_++;
  set_factor_ = c;

  const double *gnode = fix_->gnode;
  size_t m = 0;
  int node = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & bit)) continue;
    double *diag = &values_[9 * m++];
    for (int k = 0; k < 9; k++) diag[k] = (k % 4 == 0) ? vol[i] * rho[i] : 0.0;
    for (int s = springs_.first[i]; s < springs_.first[i + 1]; s++) {
      const double *e = &springs_.e[3 * s];
      const double ck = c * springs_.k[s];
      const bool unknown = gnode[springs_.partner[s]] >= 0.0;
      double *off = unknown ? &values_[9 * m++] : nullptr;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          const double kab = ck * e[a] * e[b];
          diag[3 * a + b] += kab;
          if (off) off[3 * a + b] = -kab;
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
  lagged_ = used_ && !fresh_;
  if (used_) {
    const double rate = (double) krylov / (newton > 0 ? newton : 1);
    if (solves_++ == 0) baseline_ = rate;
    else if (rate > 1.5 * baseline_ + 2.0) stale_ = true;
    if (!converged) stale_ = true;
  }
  used_ = fresh_ = false;
}

std::string SissmAmg::summary() const
{
  return fmt::format("{} set-up{} of the AMG hierarchy ({} with a new sparsity pattern)",
                     setups_, setups_ == 1 ? "" : "s", patterns_);
}

// (a solve that never reached a Newton step did not use the hierarchy: nothing to refresh)
bool SissmAmg::refresh()
{
  stale_ = true;
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
