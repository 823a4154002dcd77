// The preconditioning matrix of precond amg (doc/fix_sissm.rst, "Preconditioners";
// doc/theory.rst, "The coarse level") in 3x3 blocks over the unknowns of one process:
//   M = V (rho I + c P),   c the time scheme's force factor (h^2 for backward Euler),
// P the bond-projected stiffness of the current configuration plus the Gauss-Newton Hessian of
// the membranes' bending hinges and the (constant) Hessian of their plate bending elements
// (peri/bond_stiffness.h). Row r is the r-th unknown row in row order; its columns are global
// node numbers: the diagonal first, then its unbroken bonds' partners that are unknowns, then
// the other vertices of its hinges that are not yet among them, then the other stencil
// vertices of its plate elements that are not yet among them (no column twice). Bonds to rows
// that are not unknowns add their diagonal part only (Dirichlet rows eliminated); hinge and
// stencil vertices that are not unknowns add nothing. The glue numbers the unknowns over the
// processes and hands the blocks to the multigrid library.

#ifndef PERISISSM_SOLVERS_BLOCK_MATRIX_H
#define PERISISSM_SOLVERS_BLOCK_MATRIX_H

#include "peri/bond_stiffness.h"
#include "solvers/system.h"

#include <cstdint>
#include <vector>

namespace PeriSISSM {

// The coupling entries of each of n local rows, from the owned row of every entry (row: 4 per
// hinge, HingeCouplings::row; one per stencil vertex, PlateCouplings::row; -1 none here):
// of[first[i] .. first[i+1]-1] holds the entries whose row is i, in entry order (for hinges,
// 4 h + v: the place v (0..3) of row i in hinge h).
struct CouplingIndex {
  std::vector<int> first, of;
};
void index_couplings(const std::vector<int> &row, int n, CouplingIndex &index);

// The unknown rows of this process (rows.has(i)), and their global node numbers: node[i] of
// each of nall local rows is first + k for the k-th unknown, -1 for the others.
int count_unknowns(const Rows &rows);
void number_unknowns(const Rows &rows, int first, int nall, double *node);

// The sparsity pattern: row r holds blocks first[r] .. first[r+1]-1 with global columns col;
// row[m] is the global row of block m (the coordinate lists of a sparse matrix).
struct BlockPattern {
  std::vector<int> first, col, row;
  // the block (row r, global column gcol), -1 when it is not in the pattern (row r may be the
  // one being built: its blocks then run to the end of col)
  int find(int r, int gcol) const;
  bool operator==(const BlockPattern &o) const { return first == o.first && col == o.col; }
};

// A number naming the pattern's set of blocks (global row, global column) whatever their order
// and the process that holds them: the sum (modulo 2^64) of a 64-bit mix of each block's pair,
// which the glue sums over the processes. Two patterns with the same blocks have the same
// signature; different ones collide with probability about 2^-64.
std::uint64_t pattern_signature(const BlockPattern &pattern);

// The pattern's blocks as sorted keys (global row << 32 | global column), and whether every
// block of another pattern is among them (a pattern left by broken bonds within the one a
// matrix was made with: its blocks can be given to that matrix, whose other blocks are then
// zero).
std::vector<std::uint64_t> pattern_blocks(const BlockPattern &pattern);
bool pattern_within(const BlockPattern &pattern, const std::vector<std::uint64_t> &blocks);

// The plate elements worth their couplings in M: those with c (a_k . a_k) >= threshold rho_k V_k
// at one of their stencil vertices k (owned or ghost rows of rows.volume and rows.density), the
// term's diagonal against the mass there. A stencil reaches two rings of triangles beyond the
// bonds: its couplings double the matrix's nonzeros. The pair gives the plate edges' hinges as
// well (their pattern lies within the bonds'), and those serve where the mass is not negligible
// (measured 2026-11-30, hanging cloth at 2 ms, genalpha, Krylov iterations per step: 3038
// vertices 7.87 with every plate coupling, 7.9 with the hinges alone, 8.0 for the hinge energy;
// 33418 vertices 9.8 with the hinges alone, 11.4 with the couplings where c |a|^2 >= rho V as
// well, 9.3 for the hinge energy), while a static step needs the couplings (the clamped plate of
// examples/membranes at 0.2 s, alternate 1 cm triangles: 1160 iterations per step with them,
// 110 s against 11 s without). Decided from the element's own vertices, so that every process
// that holds an element decides alike. Output: kept (replaced).
constexpr double kPlateSignificance = 100.0;
void significant_plates(const PlateCouplings &all, const Rows &rows, double c, double threshold,
                        PlateCouplings &kept);

// Inputs: rows (the unknowns: rows.has(i), i < rows.n); node: global node number of every
// local row, owned and ghost (-1: not an unknown); springs; hinges and plates, each with its
// index (index_couplings of its row).
// Output: pattern (rebuilt).
void build_block_pattern(const Rows &rows, const double *node, const BondSprings &springs,
                         const HingeCouplings &hinges, const CouplingIndex &hinge_index,
                         const PlateCouplings &plates, const CouplingIndex &plate_index,
                         BlockPattern &pattern);

// Inputs: as build_block_pattern, the pattern built from them, c, hinges with gradients, and x
// (3 per local row). Outputs: values (9 per block of the pattern, row-major; resized) = the
// blocks of M; coords (3 per unknown, in row order; resized) = their positions, for the
// rigid-body modes of the near-null space.
void assemble_blocks(const Rows &rows, const double *node, double c, const BondSprings &springs,
                     const HingeCouplings &hinges, const CouplingIndex &hinge_index,
                     const PlateCouplings &plates, const CouplingIndex &plate_index,
                     const BlockPattern &pattern, double **x, std::vector<double> &values,
                     std::vector<double> &coords);

// b (3 per unknown, in row order; resized) = V_i r_i of the unknown rows; and back: z_i (3 per
// row) from 3 per unknown in row order
void gather_weighted(const Rows &rows, double **r, std::vector<double> &b);
void scatter_unknowns(const Rows &rows, const std::vector<double> &z, double **out);

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_BLOCK_MATRIX_H
