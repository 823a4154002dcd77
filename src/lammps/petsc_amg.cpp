/* ----------------------------------------------------------------------
   PERI-SISSM: the PETSc preconditioner (see petsc_amg.h).

   PETSc is started once per process, on first use, on the communicator of the LAMMPS instance
   that first uses it (PETSC_COMM_WORLD set to LAMMPS's world before PetscInitialize: under
   -partition, or with LAMMPS as a library on part of the processes, PETSc's collective start
   involves only the processes of that instance; LAMMPS has initialized MPI already, so PETSc
   leaves MPI alone), with its signal handler off (LAMMPS and the user's debugger keep theirs).
   Every PETSc object is created on the communicator of its instance. It is not finalized: PetscFinalize must run before MPI_Finalize, and
   a plugin has no hook there; every PETSc object of an instance is destroyed with it.
------------------------------------------------------------------------- */

#include "petsc_amg.h"

#include <petscksp.h>

#include <cstdio>
#include <stdexcept>

using namespace LAMMPS_NS;

namespace {

void check(PetscErrorCode ierr, const char *what)
{
  if (ierr == 0) return;
  const char *text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw std::runtime_error(std::string("PETSc ") + what +
                           " failed: " + (text ? text : "unknown error") + " (PETSc error " +
                           std::to_string((int) ierr) + ")");
}

void start_petsc(MPI_Comm world)
{
  PetscBool started = PETSC_FALSE;
  check(PetscInitialized(&started), "PetscInitialized");
  if (started) return;
  PETSC_COMM_WORLD = world;
  static char name[] = "lmp", nosig[] = "-no_signal_handler";
  static char *args[] = {name, nosig, nullptr};
  int argc = 2;
  char **argv = args;
  check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
  // PETSc's error handler prints a traceback and returns the code; the caller turns it into
  // a LAMMPS error
  check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
}

// The defaults, before the user's options (doc/fix_sissm.rst, "PETSc options", gives what was
// measured with and without each)
const char *const kDefaultOptions =
    "-pc_gamg_square_graph 0 -pc_gamg_threshold 0.01 -pc_gamg_coarse_eq_limit 200";

}    // namespace

struct PetscAmg::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  std::string prefix, options;
  Mat A = nullptr;
  double setup_flops = 0.0, apply_flops = 0.0;    // of the last set-up and its first application
  Vec b = nullptr, z = nullptr, coords = nullptr;
  PC pc = nullptr;
  MatNullSpace nullsp = nullptr;
  // the unknowns of this process in its own order (3 values each), and the scatter between
  // them and the matrix's vectors
  Vec mine = nullptr;
  VecScatter scatter = nullptr;
  int unknowns = 0;

  void destroy_unknowns()
  {
    if (scatter) VecScatterDestroy(&scatter);
    if (mine) VecDestroy(&mine);
  }
  void destroy_matrix()
  {
    destroy_unknowns();
    if (pc) PCDestroy(&pc);
    if (nullsp) MatNullSpaceDestroy(&nullsp);
    if (A) MatDestroy(&A);
    if (b) VecDestroy(&b);
    if (z) VecDestroy(&z);
    if (coords) VecDestroy(&coords);
  }
  // the vector of the matrix's layout := this process's unknowns' values (3 each)
  void to_matrix(const double *in, Vec out)
  {
    PetscScalar *p = nullptr;
    check(VecGetArray(mine, &p), "VecGetArray");
    for (int k = 0; k < 3 * unknowns; k++) p[k] = in[k];
    check(VecRestoreArray(mine, &p), "VecRestoreArray");
    check(VecScatterBegin(scatter, mine, out, INSERT_VALUES, SCATTER_REVERSE), "VecScatterBegin");
    check(VecScatterEnd(scatter, mine, out, INSERT_VALUES, SCATTER_REVERSE), "VecScatterEnd");
  }
  void from_matrix(Vec in, double *out)
  {
    check(VecScatterBegin(scatter, in, mine, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(scatter, in, mine, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar *q = nullptr;
    check(VecGetArrayRead(mine, &q), "VecGetArrayRead");
    for (int k = 0; k < 3 * unknowns; k++) out[k] = q[k];
    check(VecRestoreArrayRead(mine, &q), "VecRestoreArrayRead");
  }
  // the floating-point operations PETSc counts in call(), summed over the processes (at least
  // 1; collective)
  template <class Call> double flops(Call call)
  {
    PetscLogDouble before = 0.0, after = 0.0;
    PetscGetFlops(&before);
    call();
    PetscGetFlops(&after);
    double mine = after - before, all = 0.0;
    MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, comm);
    return all > 1.0 ? all : 1.0;
  }
  // the blocks (rows[m], cols[m]) := values (zeros when values is null), summed over repeats
  // and processes; a run of blocks of one row goes in as one block row (3 x 3n, row-major)
  void insert(const std::vector<int> &rows, const std::vector<int> &cols, const double *values)
  {
    check(MatZeroEntries(A), "MatZeroEntries");
    std::vector<PetscInt> c;
    std::vector<PetscScalar> v;
    for (std::size_t m = 0; m < rows.size();) {
      std::size_t end = m;
      while (end < rows.size() && rows[end] == rows[m]) end++;
      const std::size_t n = end - m;
      c.assign(cols.begin() + m, cols.begin() + end);
      v.assign(9 * n, 0.0);
      if (values)
        for (std::size_t k = 0; k < n; k++)
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) v[a * 3 * n + 3 * k + b] = values[9 * (m + k) + 3 * a + b];
      const PetscInt r = rows[m];
      check(MatSetValuesBlocked(A, 1, &r, (PetscInt) n, c.data(), v.data(), ADD_VALUES),
            "MatSetValuesBlocked");
      m = end;
    }
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
};

PetscAmg::PetscAmg(MPI_Comm comm, const std::string &prefix, const std::string &options) :
    d_(std::make_unique<Impl>())
{
  start_petsc(comm);
  d_->comm = comm;
  d_->prefix = prefix;
  d_->options = options;
  // the user's options go into the database under this instance's prefix (replacing what an
  // earlier instance of the same prefix put there)
  check(PetscOptionsPrefixPush(nullptr, prefix.c_str()), "PetscOptionsPrefixPush");
  PetscErrorCode ierr = PetscOptionsInsertString(nullptr, kDefaultOptions);
  if (!ierr) ierr = PetscOptionsInsertString(nullptr, options.c_str());
  check(PetscOptionsPrefixPop(nullptr), "PetscOptionsPrefixPop");
  check(ierr, "reading the options string");
}

PetscAmg::~PetscAmg()
{
  if (d_) d_->destroy_matrix();
}

void PetscAmg::set_pattern(int nodes, const std::vector<int> &rows, const std::vector<int> &cols)
{
  Impl &d = *d_;
  d.destroy_matrix();
  int first = 0;
  MPI_Exscan(&nodes, &first, 1, MPI_INT, MPI_SUM, d.comm);
  int me = 0;
  MPI_Comm_rank(d.comm, &me);
  if (me == 0) first = 0;
  check(MatCreate(d.comm, &d.A), "MatCreate");
  check(MatSetSizes(d.A, 3 * nodes, 3 * nodes, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetBlockSize(d.A, 3), "MatSetBlockSize");
  check(MatSetType(d.A, MATAIJ), "MatSetType");
  // blocks per block row inside and outside this process's columns
  std::vector<PetscInt> inside(nodes, 0), outside(nodes, 0);
  for (std::size_t m = 0; m < rows.size(); m++) {
    const bool in = cols[m] >= first && cols[m] < first + nodes;
    (in ? inside : outside)[rows[m] - first]++;
  }
  check(MatXAIJSetPreallocation(d.A, 3, inside.data(), outside.data(), nullptr, nullptr),
        "MatXAIJSetPreallocation");
  // the pattern, fixed: a value outside it is an error, not a new nonzero
  d.insert(rows, cols, nullptr);
  check(MatSetOption(d.A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  check(MatCreateVecs(d.A, &d.z, &d.b), "MatCreateVecs");
  check(VecDuplicate(d.b, &d.coords), "VecDuplicate");
  check(VecSetBlockSize(d.coords, 3), "VecSetBlockSize");

  check(PCCreate(d.comm, &d.pc), "PCCreate");
  check(PCSetOptionsPrefix(d.pc, d.prefix.c_str()), "PCSetOptionsPrefix");
  check(PCSetType(d.pc, PCGAMG), "PCSetType");
  check(PCGAMGSetReuseInterpolation(d.pc, PETSC_TRUE), "PCGAMGSetReuseInterpolation");
  check(PCSetFromOptions(d.pc), "PCSetFromOptions (the petsc options string)");
}

void PetscAmg::set_unknowns(const std::vector<int> &nodes)
{
  Impl &d = *d_;
  d.destroy_unknowns();
  d.unknowns = (int) nodes.size();
  std::vector<PetscInt> block(nodes.begin(), nodes.end());
  IS where = nullptr;
  check(ISCreateBlock(PETSC_COMM_SELF, 3, (PetscInt) block.size(), block.data(),
                      PETSC_COPY_VALUES, &where),
        "ISCreateBlock");
  check(VecCreateSeq(PETSC_COMM_SELF, 3 * d.unknowns, &d.mine), "VecCreateSeq");
  const PetscErrorCode ierr = VecScatterCreate(d.b, where, d.mine, nullptr, &d.scatter);
  ISDestroy(&where);
  check(ierr, "VecScatterCreate");
}

void PetscAmg::set_values(const std::vector<int> &rows, const std::vector<int> &cols,
                          const std::vector<double> &values, const double *xyz)
{
  Impl &d = *d_;
  d.insert(rows, cols, values.data());
  d.to_matrix(xyz, d.coords);
  if (d.nullsp) MatNullSpaceDestroy(&d.nullsp);
  check(MatNullSpaceCreateRigidBody(d.coords, &d.nullsp), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(d.A, d.nullsp), "MatSetNearNullSpace");
  check(PCSetOperators(d.pc, d.A, d.A), "PCSetOperators");
  d.setup_flops = d.flops([&] { check(PCSetUp(d.pc), "PCSetUp"); });
  d.apply_flops = 0.0;
}

void PetscAmg::apply(const double *bin, double *zout)
{
  Impl &d = *d_;
  d.to_matrix(bin, d.b);
  if (d.apply_flops > 0.0)
    check(PCApply(d.pc, d.b, d.z), "PCApply");
  else
    d.apply_flops = d.flops([&] { check(PCApply(d.pc, d.b, d.z), "PCApply"); });
  d.from_matrix(d.z, zout);
}

double PetscAmg::setup_in_applications() const
{
  const Impl &d = *d_;
  return d.apply_flops > 0.0 ? d.setup_flops / d.apply_flops : 0.0;
}

std::string PetscAmg::describe() const
{
  const Impl &d = *d_;
  if (!d.pc) return "not set up";
  PCType type = nullptr;
  PCGetType(d.pc, &type);
  std::string out = std::string("PETSc PC ") + (type ? type : "?");
  PetscBool isgamg = PETSC_FALSE;
  PetscObjectTypeCompare((PetscObject) d.pc, PCGAMG, &isgamg);
  if (isgamg) {
    PetscInt levels = 0;
    PCMGGetLevels(d.pc, &levels);
    out += ", " + std::to_string((int) levels) + " levels";
  }
  PetscInt m = 0, nn = 0;
  MatGetSize(d.A, &m, &nn);
  MatInfo info;
  MatGetInfo(d.A, MAT_GLOBAL_SUM, &info);
  char buf[160];
  snprintf(buf, sizeof(buf), ", matrix %d x %d with %.0f nonzeros", (int) m, (int) nn,
           info.nz_used);
  return out + buf;
}
