// The preconditioning matrix of precond amg in 3x3 blocks (see block_matrix.h).

#include "solvers/block_matrix.h"

#include <algorithm>

namespace PeriSISSM {

int count_unknowns(const Rows &rows)
{
  int count = 0;
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i)) count++;
  return count;
}

void number_unknowns(const Rows &rows, int first, int nall, double *node)
{
  for (int i = 0; i < nall; i++) node[i] = -1.0;
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i)) node[i] = first++;
}

void index_couplings(const std::vector<int> &row, int n, CouplingIndex &index)
{
  index.first.assign(n + 1, 0);
  const int entries = (int) row.size();
  for (int q = 0; q < entries; q++)
    if (row[q] >= 0) index.first[row[q] + 1]++;
  for (int i = 0; i < n; i++) index.first[i + 1] += index.first[i];
  index.of.resize(index.first[n]);
  std::vector<int> next(index.first.begin(), index.first.end() - 1);
  for (int q = 0; q < entries; q++)
    if (row[q] >= 0) index.of[next[row[q]]++] = q;
}

// the plate element of entry k
static int element_of(const PlateCouplings &plates, int k)
{
  const auto after = std::upper_bound(plates.first.begin(), plates.first.end(), k);
  return (int) (after - plates.first.begin()) - 1;
}

void significant_plates(const PlateCouplings &all, const Rows &rows, double c, double threshold,
                        PlateCouplings &kept)
{
  kept.first.assign(1, 0);
  kept.vertex.clear();
  kept.row.clear();
  kept.a.clear();
  for (int e = 0; e < all.count(); e++) {
    bool significant = false;
    for (int q = all.first[e]; q < all.first[e + 1] && !significant; q++) {
      const double *a = &all.a[3 * q];
      const int v = all.vertex[q];
      significant = c * (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) >=
          threshold * rows.density[v] * rows.volume[v];
    }
    if (!significant) continue;
    kept.vertex.insert(kept.vertex.end(), all.vertex.begin() + all.first[e],
                       all.vertex.begin() + all.first[e + 1]);
    kept.row.insert(kept.row.end(), all.row.begin() + all.first[e], all.row.begin() + all.first[e + 1]);
    kept.a.insert(kept.a.end(), all.a.begin() + 3 * all.first[e], all.a.begin() + 3 * all.first[e + 1]);
    kept.first.push_back((int) kept.vertex.size());
  }
}

int BlockPattern::find(int r, int gcol) const
{
  const int end = r + 1 < (int) first.size() ? first[r + 1] : (int) col.size();
  for (int m = first[r]; m < end; m++)
    if (col[m] == gcol) return m;
  return -1;
}

// adds to row r, the one being built, the columns of the m vertices v that are unknowns and
// not yet in it
static void add_new_columns(const double *node, const int *v, int m, int r, BlockPattern &pattern)
{
  for (int b = 0; b < m; b++) {
    const int gj = (int) node[v[b]];
    if (gj >= 0 && pattern.find(r, gj) < 0) pattern.col.push_back(gj);
  }
}

void build_block_pattern(const Rows &rows, const double *node, const BondSprings &springs,
                         const HingeCouplings &hinges, const CouplingIndex &hinge_index,
                         const PlateCouplings &plates, const CouplingIndex &plate_index,
                         BlockPattern &pattern)
{
  pattern.first.assign(1, 0);
  pattern.col.clear();
  pattern.row.clear();
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    const int gi = (int) node[i];
    const int r = (int) pattern.first.size() - 1;
    pattern.col.push_back(gi);
    for (int s = springs.first[i]; s < springs.first[i + 1]; s++) {
      const int gj = (int) node[springs.partner[s]];
      if (gj >= 0) pattern.col.push_back(gj);
    }
    for (int q = hinge_index.first[i]; q < hinge_index.first[i + 1]; q++)
      add_new_columns(node, &hinges.vertex[4 * (hinge_index.of[q] / 4)], 4, r, pattern);
    for (int q = plate_index.first[i]; q < plate_index.first[i + 1]; q++) {
      const int e = element_of(plates, plate_index.of[q]);
      add_new_columns(node, &plates.vertex[plates.first[e]], plates.first[e + 1] - plates.first[e],
                      r, pattern);
    }
    pattern.first.push_back((int) pattern.col.size());
    pattern.row.resize(pattern.col.size(), gi);
  }
}

static std::uint64_t block_key(int row, int col)
{
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(row)) << 32) |
      static_cast<std::uint32_t>(col);
}

std::vector<std::uint64_t> pattern_blocks(const BlockPattern &pattern)
{
  std::vector<std::uint64_t> keys(pattern.col.size());
  for (std::size_t m = 0; m < keys.size(); m++) keys[m] = block_key(pattern.row[m], pattern.col[m]);
  std::sort(keys.begin(), keys.end());
  return keys;
}

bool pattern_within(const BlockPattern &pattern, const std::vector<std::uint64_t> &blocks)
{
  for (std::size_t m = 0; m < pattern.col.size(); m++)
    if (!std::binary_search(blocks.begin(), blocks.end(),
                            block_key(pattern.row[m], pattern.col[m])))
      return false;
  return true;
}

std::uint64_t pattern_signature(const BlockPattern &pattern)
{
  std::uint64_t sum = 0;
  for (std::size_t m = 0; m < pattern.col.size(); m++) {
    // splitmix64's finalizer of the pair
    std::uint64_t z = block_key(pattern.row[m], pattern.col[m]);
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    sum += z ^ (z >> 31);
  }
  return sum;
}

// the block of row r in column gj among values, null when gj is not an unknown (held: no
// column)
static double *block_at(const BlockPattern &pattern, int r, int gj, std::vector<double> &values)
{
  return gj < 0 ? nullptr : &values[9 * pattern.find(r, gj)];
}

void assemble_blocks(const Rows &rows, const double *node, double c, const BondSprings &springs,
                     const HingeCouplings &hinges, const CouplingIndex &hinge_index,
                     const PlateCouplings &plates, const CouplingIndex &plate_index,
                     const BlockPattern &pattern, double **x, std::vector<double> &values,
                     std::vector<double> &coords)
{
  values.assign(9 * pattern.col.size(), 0.0);
  coords.assign(3 * (pattern.first.size() - 1), 0.0);
  const double *rho = rows.density, *vol = rows.volume;
  int r = 0;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    int m = pattern.first[r];
    double *diag = &values[9 * m++];
    for (int k = 0; k < 9; k += 4) diag[k] = vol[i] * rho[i];
    // (membranes: the stabilization's block S as well, its 6 values at (a, b) by kSym)
    static constexpr int kSym[9] = {0, 3, 4, 3, 1, 5, 4, 5, 2};
    for (int s = springs.first[i]; s < springs.first[i + 1]; s++) {
      const double *e = &springs.e[3 * s];
      const double *st = springs.s.empty() ? nullptr : &springs.s[6 * s];
      const double ck = c * springs.k[s];
      const bool unknown = node[springs.partner[s]] >= 0.0;
      double *off = unknown ? &values[9 * m++] : nullptr;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          double kab = ck * e[a] * e[b];
          if (st) kab += c * st[kSym[3 * a + b]];
          diag[3 * a + b] += kab;
          if (off) off[3 * a + b] -= kab;
        }
    }
    // the hinges: row v of c g g^T, blocks g_v g_b^T (g = sqrt(2 c_hinge) grad theta)
    for (int q = hinge_index.first[i]; q < hinge_index.first[i + 1]; q++) {
      const int h = hinge_index.of[q] / 4, v = hinge_index.of[q] % 4;
      const double *g = &hinges.grad[12 * h];
      for (int b = 0; b < 4; b++) {
        const int j = hinges.vertex[4 * h + b];
        double *blk = block_at(pattern, r, b == v ? (int) node[i] : (int) node[j], values);
        if (!blk) continue;
        for (int a = 0; a < 3; a++)
          for (int d = 0; d < 3; d++) blk[3 * a + d] += c * g[3 * v + a] * g[3 * b + d];
      }
    }
    // the plate elements: row k of c H, blocks c (a_k . a_l) I
    for (int q = plate_index.first[i]; q < plate_index.first[i + 1]; q++) {
      const int k = plate_index.of[q], e = element_of(plates, k);
      const double *ak = &plates.a[3 * k];
      for (int l = plates.first[e]; l < plates.first[e + 1]; l++) {
        const int j = plates.vertex[l];
        double *blk = block_at(pattern, r, l == k ? (int) node[i] : (int) node[j], values);
        if (!blk) continue;
        const double *al = &plates.a[3 * l];
        const double h = c * (ak[0] * al[0] + ak[1] * al[1] + ak[2] * al[2]);
        for (int d = 0; d < 9; d += 4) blk[d] += h;
      }
    }
    for (int k = 0; k < 3; k++) coords[3 * r + k] = x[i][k];
    r++;
  }
}

void gather_weighted(const Rows &rows, double **r, std::vector<double> &b)
{
  b.clear();
  for (int i = 0; i < rows.n; i++)
    if (rows.has(i))
      for (int k = 0; k < 3; k++) b.push_back(rows.volume[i] * r[i][k]);
}

void scatter_unknowns(const Rows &rows, const std::vector<double> &z, double **out)
{
  int node = 0;
  for (int i = 0; i < rows.n; i++) {
    if (!rows.has(i)) continue;
    for (int k = 0; k < 3; k++) out[i][k] = z[3 * node + k];
    node++;
  }
}

}    // namespace PeriSISSM
