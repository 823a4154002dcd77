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
  Vec b = nullptr, z = nullptr, coords = nullptr;
  PC pc = nullptr;
  MatNullSpace nullsp = nullptr;
  int nodes = 0;
  bool options_inserted = false;

  void destroy_matrix()
  {
    if (pc) PCDestroy(&pc);
    if (nullsp) MatNullSpaceDestroy(&nullsp);
    if (A) MatDestroy(&A);
    if (b) VecDestroy(&b);
    if (z) VecDestroy(&z);
    if (coords) VecDestroy(&coords);
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
  d.nodes = nodes;
  const PetscInt n = 3 * nodes;
  check(MatCreate(d.comm, &d.A), "MatCreate");
  check(MatSetSizes(d.A, n, n, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetBlockSize(d.A, 3), "MatSetBlockSize");
  check(MatSetType(d.A, MATAIJ), "MatSetType");
  // one COO entry per scalar: block (r, c) holds rows 3r+a, columns 3c+b
  const size_t nb = rows.size();
  std::vector<PetscInt> ci(9 * nb), cj(9 * nb);
  for (size_t m = 0; m < nb; m++)
    for (int a = 0; a < 3; a++)
      for (int c = 0; c < 3; c++) {
        ci[9 * m + 3 * a + c] = 3 * rows[m] + a;
        cj[9 * m + 3 * a + c] = 3 * cols[m] + c;
      }
  check(MatSetPreallocationCOO(d.A, (PetscCount) ci.size(), ci.data(), cj.data()),
        "MatSetPreallocationCOO");
  check(MatCreateVecs(d.A, &d.z, &d.b), "MatCreateVecs");
  check(VecDuplicate(d.b, &d.coords), "VecDuplicate");
  check(VecSetBlockSize(d.coords, 3), "VecSetBlockSize");

  check(PCCreate(d.comm, &d.pc), "PCCreate");
  check(PCSetOptionsPrefix(d.pc, d.prefix.c_str()), "PCSetOptionsPrefix");
  check(PCSetType(d.pc, PCGAMG), "PCSetType");
  check(PCGAMGSetReuseInterpolation(d.pc, PETSC_TRUE), "PCGAMGSetReuseInterpolation");
  check(PCSetFromOptions(d.pc), "PCSetFromOptions (the petsc options string)");
}

void PetscAmg::set_values(const std::vector<double> &values, const double *xyz)
{
  Impl &d = *d_;
  check(MatSetValuesCOO(d.A, values.data(), INSERT_VALUES), "MatSetValuesCOO");
  PetscScalar *c = nullptr;
  check(VecGetArray(d.coords, &c), "VecGetArray");
  for (int k = 0; k < 3 * d.nodes; k++) c[k] = xyz[k];
  check(VecRestoreArray(d.coords, &c), "VecRestoreArray");
  if (d.nullsp) MatNullSpaceDestroy(&d.nullsp);
  check(MatNullSpaceCreateRigidBody(d.coords, &d.nullsp), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(d.A, d.nullsp), "MatSetNearNullSpace");
  check(PCSetOperators(d.pc, d.A, d.A), "PCSetOperators");
  check(PCSetUp(d.pc), "PCSetUp");
}

void PetscAmg::apply(const double *bin, double *zout)
{
  Impl &d = *d_;
  const int n = 3 * d.nodes;
  PetscScalar *p = nullptr;
  check(VecGetArray(d.b, &p), "VecGetArray");
  for (int k = 0; k < n; k++) p[k] = bin[k];
  check(VecRestoreArray(d.b, &p), "VecRestoreArray");
  check(PCApply(d.pc, d.b, d.z), "PCApply");
  const PetscScalar *q = nullptr;
  check(VecGetArrayRead(d.z, &q), "VecGetArrayRead");
  for (int k = 0; k < n; k++) zout[k] = q[k];
  check(VecRestoreArrayRead(d.z, &q), "VecRestoreArrayRead");
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
