// The preconditioning matrix of precond amg in 3x3 blocks (solvers/block_matrix.h), on a small
// hand-made set of rows: four owned rows of which three are unknowns, ghosts, springs along
// the bonds, one bending hinge and (added by some tests) two overlapping plate elements. The
// pattern is checked column by column, and the assembled matrix against the same matrix written
// out densely from its definition
//   M = V rho I + c (sum over springs of k e e^T + S, -(k e e^T + S) off the diagonal)
//       + c g g^T + c sum over plate elements of (a_k . a_l) I,
// S the membranes' stabilization blocks (added by one test; none otherwise).

#include "solvers/block_matrix.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using namespace PeriSISSM;

// rows 0, 1, 3 are unknowns (global nodes 10, 11, 12), row 2 is held, rows 4 and 5 ghost
// unknowns (global nodes 20, 30) of other processes, row 6 a held ghost
constexpr int kLocal = 7;
struct Scene {
  int mask[4] = {1, 1, 0, 1};
  double volume[4] = {2.0, 3.0, 4.0, 5.0};
  double density[4] = {7.0, 11.0, 13.0, 17.0};
  double node[kLocal] = {10, 11, -1, 12, 20, 30, -1};
  double xdata[kLocal][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                             {2, 1, 0}, {2, 0, 0}, {0, 2, 0}};
  double *x[kLocal] = {xdata[0], xdata[1], xdata[2], xdata[3], xdata[4], xdata[5], xdata[6]};
  Rows rows;
  BondSprings springs;
  HingeCouplings hinges;
  CouplingIndex index;
  PlateCouplings plates;    // none until add_plates()
  CouplingIndex plate_index;

  Scene()
  {
    rows.n = 4;
    rows.mask = mask;
    rows.bit = 1;
    rows.volume = volume;
    rows.density = density;
    // springs of each owned row (partners in family order): 0-1, 0-2, 1-0, 1-3, 2-0, 3-1, 3-4
    springs.first = {0, 2, 4, 5, 7};
    springs.partner = {1, 2, 0, 3, 0, 1, 4};
    springs.k = {1.5, 2.5, 1.5, 0.5, 2.5, 0.5, 4.0};
    for (int s = 0; s < 7; s++) {
      const int i = s < 2 ? 0 : s < 4 ? 1 : s < 5 ? 2 : 3;
      const int j = springs.partner[s];
      double e[3], len = 0.0;
      for (int k = 0; k < 3; k++) {
        e[k] = x[j][k] - x[i][k];
        len += e[k] * e[k];
      }
      for (int k = 0; k < 3; k++) springs.e.push_back(e[k] / std::sqrt(len));
    }
    // one hinge over rows 0, 1, 2 and ghost 4; row 3 takes no part: vertex 2 (held) has no row
    // here, nor the ghost
    hinges.vertex = {0, 1, 2, 4};
    hinges.row = {0, 1, -1, -1};
    for (int k = 0; k < 12; k++) hinges.grad.push_back(0.1 * (k + 1) * (k % 2 ? -1.0 : 1.0));
    index_couplings(hinges.row, rows.n, index);
    plates.first = {0};
    index_couplings(plates.row, rows.n, plate_index);
  }

  // two plate elements sharing the vertices 0, 1, 3 and the ghost 5: element 0 over 0, 1, 3,
  // ghost 5 and the held row 2 (its row listed: the pattern skips it), element 1 over 3, ghost
  // 4, the held ghost 6, 1, 0 and ghost 5
  void add_plates()
  {
    plates.first = {0, 5, 11};
    plates.vertex = {0, 1, 3, 5, 2, 3, 4, 6, 1, 0, 5};
    plates.row = {0, 1, 3, -1, 2, 3, -1, -1, 1, 0, -1};
    plates.a.clear();
    for (int k = 0; k < 33; k++)
      plates.a.push_back(0.05 * (k % 7 + 1) * (k % 3 ? 1.0 : -1.0) + 0.01 * k);
    index_couplings(plates.row, rows.n, plate_index);
  }
  // a symmetric stabilization block per spring (xx yy zz xy xz yz), the same for both ends
  void add_stabilization()
  {
    const double pair_value[7] = {0.3, 0.7, 0.3, 0.2, 0.7, 0.2, 0.9};
    springs.s.clear();
    for (int t = 0; t < 7; t++) {
      const double v = pair_value[t];
      const double block[6] = {v, 2.0 * v, 0.5 * v, -0.1 * v, 0.3 * v, 0.05 * v};
      springs.s.insert(springs.s.end(), block, block + 6);
    }
  }
};

// the blocks of the pattern's rows by global row and column, for comparisons across rows
const double *block_of(const BlockPattern &p, const std::vector<double> &values, int grow, int gcol)
{
  for (std::size_t m = 0; m < p.col.size(); m++)
    if (p.row[m] == grow && p.col[m] == gcol) return &values[9 * m];
  return nullptr;
}

TEST(BlockMatrix, HingeIndexListsEachRowsPlaces)
{
  Scene s;
  EXPECT_EQ(s.index.first, (std::vector<int>{0, 1, 2, 2, 2}));
  EXPECT_EQ(s.index.of, (std::vector<int>{0, 1}));    // 4 h + v: hinge 0, places 0 and 1
  EXPECT_EQ(s.plate_index.first, (std::vector<int>{0, 0, 0, 0, 0}));
  EXPECT_TRUE(s.plate_index.of.empty());
}

TEST(BlockMatrix, PlateIndexListsEachRowsEntries)
{
  Scene s;
  s.add_plates();
  // row 0: entries 0 (element 0) and 9 (element 1); row 1: 1, 8; row 2 (held): 4; row 3: 2, 5
  EXPECT_EQ(s.plate_index.first, (std::vector<int>{0, 2, 4, 5, 7}));
  EXPECT_EQ(s.plate_index.of, (std::vector<int>{0, 9, 1, 8, 4, 2, 5}));
}

TEST(BlockMatrix, PatternHasDiagonalFirstThenPartnersThenHingeVertices)
{
  Scene s;
  BlockPattern p;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, p);
  // row 0 (node 10): diagonal, bond partner 11 (2 is held), hinge vertices 10, 11, 20: only
  // 20 is new; row 1 (node 11): 11, 10, 12, then hinge vertex 20; row 3 (node 12): 12, 11, 20
  EXPECT_EQ(p.first, (std::vector<int>{0, 3, 7, 10}));
  EXPECT_EQ(p.col, (std::vector<int>{10, 11, 20, 11, 10, 12, 20, 12, 11, 20}));
  EXPECT_EQ(p.row, (std::vector<int>{10, 10, 10, 11, 11, 11, 11, 12, 12, 12}));
  EXPECT_EQ(p.find(1, 12), 5);
  EXPECT_EQ(p.find(2, 10), -1);
  BlockPattern q;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, q);
  EXPECT_TRUE(p == q);
  s.node[4] = 21;    // the ghost renumbered: another pattern
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, q);
  EXPECT_FALSE(p == q);
}

TEST(BlockMatrix, PatternAddsThePlateStencilsAfterTheHinges)
{
  Scene s;
  s.add_plates();
  BlockPattern p;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, p);
  // row 0 (node 10): 10, 11 (bond), 20 (hinge), then 12 and 30 from element 0 (element 1 adds
  // nothing new); row 1 (11): 11, 10, 12, 20, then 30; row 3 (12): 12, 11, 20, then 10 and 30.
  // The held row 2 and the held ghost 6 are no column.
  EXPECT_EQ(p.first, (std::vector<int>{0, 5, 10, 15}));
  EXPECT_EQ(p.col, (std::vector<int>{10, 11, 20, 12, 30, 11, 10, 12, 20, 30, 12, 11, 20, 10, 30}));
  EXPECT_EQ(p.row, (std::vector<int>{10, 10, 10, 10, 10, 11, 11, 11, 11, 11, 12, 12, 12, 12, 12}));

  // in general: the diagonal first, no column twice, a column for every unknown stencil vertex
  // of the row's elements and none for the others
  const int local_of_row[3] = {0, 1, 3};
  for (int r = 0; r < 3; r++) {
    const int i = local_of_row[r];
    std::vector<int> cols(p.col.begin() + p.first[r], p.col.begin() + p.first[r + 1]);
    EXPECT_EQ(cols[0], (int) s.node[i]);
    std::vector<int> sorted = cols;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) << r;
    for (int c : cols) EXPECT_GE(c, 0);
    for (int e = 0; e < s.plates.count(); e++) {
      bool has = false;
      for (int k = s.plates.first[e]; k < s.plates.first[e + 1]; k++)
        has = has || s.plates.row[k] == i;
      if (!has) continue;
      for (int k = s.plates.first[e]; k < s.plates.first[e + 1]; k++) {
        const int gj = (int) s.node[s.plates.vertex[k]];
        if (gj >= 0) { EXPECT_GE(p.find(r, gj), 0) << "row " << r << " column " << gj; }
      }
    }
  }

  // the ghost 5 replaced by the held ghost 6 in both elements: column 30 leaves every row
  BlockPattern q;
  s.plates.vertex[3] = s.plates.vertex[10] = 6;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, q);
  EXPECT_FALSE(p == q);
  EXPECT_EQ(std::count(q.col.begin(), q.col.end(), 30), 0);
  EXPECT_EQ(q.col.size(), p.col.size() - 3);
}

// The signature names the set of blocks: the same blocks split over two processes in another
// order sum to the signature of the whole; a block moved to another column changes it.
TEST(BlockMatrix, SignatureIsTheSetOfBlocksWhateverTheirOrderAndProcess)
{
  Scene s;
  BlockPattern whole;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, whole);
  const std::uint64_t sig = pattern_signature(whole);
  BlockPattern a, b;    // rows 11 and 10 on one process (in that order), 12 on the other
  for (int m : {3, 4, 5, 6, 0, 1, 2}) {
    a.row.push_back(whole.row[m]);
    a.col.push_back(whole.col[m]);
  }
  for (int m : {9, 7, 8}) {
    b.row.push_back(whole.row[m]);
    b.col.push_back(whole.col[m]);
  }
  EXPECT_EQ(pattern_signature(a) + pattern_signature(b), sig);
  BlockPattern moved = whole;
  moved.col[2] = 21;
  EXPECT_NE(pattern_signature(moved), sig);
  BlockPattern transposed = whole;    // (10, 11) and (11, 10) swapped for (11, 10), (10, 11)
  std::swap(transposed.row[1], transposed.col[1]);
  std::swap(transposed.row[4], transposed.col[4]);
  EXPECT_EQ(pattern_signature(transposed), sig);
  transposed.row[1] = 12;    // a block of row 12 instead of row 11
  EXPECT_NE(pattern_signature(transposed), sig);
}

TEST(BlockMatrix, APatternLeftByBrokenBondsLiesWithinTheWholeOne)
{
  Scene s;
  BlockPattern whole;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, whole);
  const std::vector<std::uint64_t> blocks = pattern_blocks(whole);
  ASSERT_EQ(blocks.size(), whole.col.size());
  EXPECT_TRUE(std::is_sorted(blocks.begin(), blocks.end()));
  EXPECT_TRUE(pattern_within(whole, blocks));

  // the bond 1-3 broken (springs 1->3 and 3->1 gone): rows 11 and 12 lose their coupling
  BondSprings broken;
  broken.first = {0, 2, 3, 4, 5};
  broken.partner = {1, 2, 0, 0, 4};
  for (int s2 : {0, 1, 2, 4, 6}) {
    broken.k.push_back(s.springs.k[s2]);
    for (int k = 0; k < 3; k++) broken.e.push_back(s.springs.e[3 * s2 + k]);
  }
  BlockPattern fewer;
  build_block_pattern(s.rows, s.node, broken, s.hinges, s.index, s.plates, s.plate_index, fewer);
  ASSERT_LT(fewer.col.size(), whole.col.size());
  EXPECT_TRUE(pattern_within(fewer, blocks));
  EXPECT_FALSE(pattern_within(whole, pattern_blocks(fewer)));

  BlockPattern other = whole;    // a block that the whole pattern does not have
  other.col[1] = 21;
  EXPECT_FALSE(pattern_within(other, blocks));
}

// The matrix of the scene written out densely from its definition over all local rows (row
// and column by local index), and the blocks assembled from the pattern: every block of every
// unknown row's column that is an unknown is in the pattern with the dense value, and a column
// missing from the pattern has a zero block; the held rows are no column.
void expect_dense_definition(Scene &s)
{
  BlockPattern p;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, p);
  const double c = 0.3;
  std::vector<double> values, coords;
  assemble_blocks(s.rows, s.node, c, s.springs, s.hinges, s.index, s.plates, s.plate_index, p, s.x,
                  values, coords);
  ASSERT_EQ(values.size(), 9 * p.col.size());
  ASSERT_EQ(coords.size(), 9u);

  const int nl = kLocal;
  std::vector<double> dense(9 * nl * nl, 0.0);
  auto at = [&](int i, int j, int a, int b) -> double & {
    return dense[((3 * i + a) * nl + j) * 3 + b];
  };
  const int owner[7] = {0, 0, 1, 1, 2, 3, 3};
  for (int i = 0; i < 4; i++)
    for (int a = 0; a < 3; a++) at(i, i, a, a) = s.volume[i] * s.density[i];
  for (int t = 0; t < 7; t++) {
    const int i = owner[t], j = s.springs.partner[t];
    const double *e = &s.springs.e[3 * t];
    const int sym[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) {
        const double st = s.springs.s.empty() ? 0.0 : s.springs.s[6 * t + sym[a][b]];
        at(i, i, a, b) += c * (s.springs.k[t] * e[a] * e[b] + st);
        at(i, j, a, b) -= c * (s.springs.k[t] * e[a] * e[b] + st);
      }
  }
  for (int v = 0; v < 2; v++)    // the hinge's rows of owned unknowns 0 and 1
    for (int b = 0; b < 4; b++)
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++)
          at(v, s.hinges.vertex[b], a, d) +=
              c * s.hinges.grad[3 * v + a] * s.hinges.grad[3 * b + d];
  // the plate elements whole, every pair of stencil vertices (k, l): c (a_k . a_l) I
  for (int e = 0; e < s.plates.count(); e++)
    for (int k = s.plates.first[e]; k < s.plates.first[e + 1]; k++)
      for (int l = s.plates.first[e]; l < s.plates.first[e + 1]; l++) {
        double dot = 0.0;
        for (int a = 0; a < 3; a++) dot += s.plates.a[3 * k + a] * s.plates.a[3 * l + a];
        for (int a = 0; a < 3; a++) at(s.plates.vertex[k], s.plates.vertex[l], a, a) += c * dot;
      }

  const int local_of_row[3] = {0, 1, 3};
  for (int r = 0; r < 3; r++) {
    const int i = local_of_row[r];
    for (int j = 0; j < nl; j++) {
      const int m = p.find(r, (int) s.node[j]);
      if (s.node[j] < 0) continue;
      double norm = 0.0;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          const double want = at(i, j, a, b);
          norm += std::fabs(want);
          if (m >= 0) { EXPECT_NEAR(values[9 * m + 3 * a + b], want, 1e-13) << r << " " << j; }
        }
      if (m < 0) { EXPECT_EQ(norm, 0.0) << "row " << r << " misses column " << s.node[j]; }
    }
    for (int k = 0; k < 3; k++) EXPECT_EQ(coords[3 * r + k], s.x[i][k]);
  }
}

TEST(BlockMatrix, AssembledBlocksMatchTheDenseDefinition)
{
  Scene s;
  expect_dense_definition(s);
}

TEST(BlockMatrix, AssembledBlocksWithPlatesMatchTheDenseDefinition)
{
  Scene s;
  s.add_plates();
  expect_dense_definition(s);
}

TEST(BlockMatrix, AssembledBlocksWithStabilizationMatchTheDenseDefinition)
{
  Scene s;
  s.add_plates();
  s.add_stabilization();
  expect_dense_definition(s);
}

// Between two unknowns of this process the blocks (r, s) and (s, r) are each other's
// transposes, and the plates made the matrix no less so.
TEST(BlockMatrix, AssembledMatrixIsSymmetric)
{
  Scene s;
  s.add_plates();
  BlockPattern p;
  build_block_pattern(s.rows, s.node, s.springs, s.hinges, s.index, s.plates, s.plate_index, p);
  std::vector<double> values, coords;
  assemble_blocks(s.rows, s.node, 0.7, s.springs, s.hinges, s.index, s.plates, s.plate_index, p,
                  s.x, values, coords);
  int pairs = 0;
  for (int gi : {10, 11, 12})
    for (int gj : {10, 11, 12}) {
      const double *ij = block_of(p, values, gi, gj), *ji = block_of(p, values, gj, gi);
      ASSERT_EQ(ij == nullptr, ji == nullptr) << gi << " " << gj;
      if (!ij) continue;
      pairs++;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
          EXPECT_NEAR(ij[3 * a + b], ji[3 * b + a], 1e-13) << gi << " " << gj;
    }
  EXPECT_EQ(pairs, 9);    // the plates couple all three unknowns
}

TEST(BlockMatrix, GatherAndScatterFollowTheUnknownRows)
{
  Scene s;
  double rdata[4][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}};
  double *r[4] = {rdata[0], rdata[1], rdata[2], rdata[3]};
  std::vector<double> b;
  gather_weighted(s.rows, r, b);
  EXPECT_EQ(b, (std::vector<double>{2, 4, 6, 12, 15, 18, 50, 55, 60}));
  double zdata[4][3] = {};
  double *z[4] = {zdata[0], zdata[1], zdata[2], zdata[3]};
  scatter_unknowns(s.rows, b, z);
  EXPECT_EQ(zdata[1][2], 18.0);
  EXPECT_EQ(zdata[2][0], 0.0);    // held: untouched
  EXPECT_EQ(zdata[3][1], 55.0);
}

TEST(BlockMatrix, UnknownsAreNumberedInRowOrderFromTheFirst)
{
  Scene s;
  EXPECT_EQ(count_unknowns(s.rows), 3);
  double node[6] = {7, 7, 7, 7, 7, 7};
  number_unknowns(s.rows, 10, 5, node);
  for (int i = 0; i < 4; i++) EXPECT_EQ(node[i], s.node[i]) << i;
  EXPECT_EQ(node[4], -1.0);    // a ghost: its owner numbers it
  EXPECT_EQ(node[5], 7.0);     // beyond nall: untouched
}

}    // namespace

// A plate element is kept when c |a_k|^2 >= threshold rho_k V_k at one of its vertices (a ghost
// counts: every process holding the element decides alike), with its entries unchanged.
TEST(BlockMatrix, OnlyPlatesWhoseStiffnessRivalsTheMassAreKept)
{
  double volume[4] = {1.0, 2.0, 1.0, 4.0}, density[4] = {1.0, 1.0, 3.0, 1.0};
  int mask[4] = {1, 1, 1, 1};
  Rows rows;
  rows.n = 2;
  rows.mask = mask;
  rows.bit = 1;
  rows.volume = volume;
  rows.density = density;
  PlateCouplings all;
  // element 0 over rows 0, 1 (|a|^2 = 0.25, 1): rho V = 1, 2; element 1 over 1 and ghost 3
  // (|a|^2 = 1, 16: rho V = 2, 4); element 2 over ghost 2 and 0 (|a|^2 = 4, 0.01: rho V = 3, 1)
  all.first = {0, 2, 4, 6};
  all.vertex = {0, 1, 1, 3, 2, 0};
  all.row = {0, 1, 1, -1, -1, 0};
  all.a = {0.5, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 4, 0, 2, 0, 0.1, 0, 0};
  PlateCouplings kept;
  significant_plates(all, rows, 1.0, 1.0, kept);    // c |a|^2 / (rho V): 0.25 0.5 | 0.5 4 | 1.33 0.01
  EXPECT_EQ(kept.first, (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(kept.vertex, (std::vector<int>{1, 3, 2, 0}));
  EXPECT_EQ(kept.row, (std::vector<int>{1, -1, -1, 0}));
  EXPECT_EQ(kept.a, std::vector<double>(all.a.begin() + 6, all.a.end()));
  significant_plates(all, rows, 3.0, 1.0, kept);    // all three at c = 3 (0.5 x 3 >= 1)
  EXPECT_EQ(kept.count(), 3);
  significant_plates(all, rows, 0.1, 1.0, kept);    // none at c = 0.1 (4 x 0.1 < 1)
  EXPECT_EQ(kept.count(), 0);
  EXPECT_EQ(kept.first, (std::vector<int>{0}));
}
