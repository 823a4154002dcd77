/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   A distributed algebraic multigrid preconditioner from PETSc (smoothed aggregation, PCGAMG,
   by default): z = M^-1 b for a sparse symmetric matrix M with three unknowns per node (block
   size 3), assembled from coordinate (COO) lists in global node numbers, with the six
   rigid-body modes of the nodes' coordinates as its near-null space. The matrix's pattern and
   its rows' processes are fixed when it is made; each process then gives the values of its
   unknowns' rows and its unknowns' entries of b and z wherever the matrix holds them, so the
   hierarchy outlives nodes changing processes. Knows MPI and PETSc, not LAMMPS: fix sissm
   numbers the nodes and fills the lists (fix_sissm_amg.cpp). Errors are
   thrown as std::runtime_error with PETSc's message.
------------------------------------------------------------------------- */

#ifndef LMP_PERISISSM_PETSC_AMG_H
#define LMP_PERISISSM_PETSC_AMG_H

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class PetscAmg {
 public:
  // comm: the processes that share the matrix; prefix: options prefix of this instance in
  // PETSc's options database (e.g. "sissm_ID_"); options: PETSc options given by the user,
  // without the prefix ("-pc_type hypre -pc_hypre_type boomeramg"), applied after the defaults
  PetscAmg(MPI_Comm comm, const std::string &prefix, const std::string &options);
  ~PetscAmg();
  PetscAmg(const PetscAmg &) = delete;
  PetscAmg &operator=(const PetscAmg &) = delete;

  // A new matrix (and no hierarchy): nodes: the nodes this process owns in the matrix (global
  // numbers first .. first + nodes - 1, numbered contiguously over the processes in rank
  // order); rows, cols: global node numbers of the 3x3 blocks of the pattern this process
  // holds, each of its rows one of its own nodes. Later values may come from other processes
  // (set_values), the pattern's blocks stay the only ones.
  void set_pattern(int nodes, const std::vector<int> &rows, const std::vector<int> &cols);
  // the unknowns of this process, in its order of b and z (apply) and of the coordinates
  // (set_values): their global node numbers, owned in the matrix by any process. Collective.
  void set_unknowns(const std::vector<int> &nodes);
  // values: 9 per block (rows[m], cols[m]), row-major, blocks of set_pattern's pattern held by
  // any process (entries of repeated blocks are summed); coords: 3 per unknown (the near-null
  // space). Then the preconditioner is set up (the first time: the hierarchy; later: again,
  // reusing the interpolation when the options allow it). Collective.
  void set_values(const std::vector<int> &rows, const std::vector<int> &cols,
                  const std::vector<double> &values, const double *coords);
  // z = M^-1 b, 3 values per unknown each. Collective.
  void apply(const double *b, double *z);
  // the work of the last set_values() over that of the first application after it (PETSc's
  // count of floating-point operations, all processes), 0 before both: what a set-up costs in
  // applications
  double setup_in_applications() const;

  // what PETSc built, one line (after set_values): preconditioner type, levels, the matrix's
  // size and nonzeros. Collective: every process must call it.
  std::string describe() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}    // namespace LAMMPS_NS

#endif
