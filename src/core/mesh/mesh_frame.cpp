/* PERI-SISSM core: one frame of a mesh dump (mesh/mesh_frame.h). */
#include "mesh/mesh_frame.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

namespace PeriSISSM {

namespace {

  // the triangles' order in a frame: mesh id, then the vertex IDs
  bool triangle_before(const FrameTriangle &a, const FrameTriangle &b)
  {
    return std::tie(a.mesh, a.v[0], a.v[1], a.v[2]) < std::tie(b.mesh, b.v[0], b.v[1], b.v[2]);
  }

}    // namespace

MeshFrame assemble_frame(const std::vector<double> &rows, int ncolumns,
                         const std::vector<FrameTriangle> &triangles)
{
  if (ncolumns < kFrameRowHead)
    throw std::invalid_argument("mesh frame: " + std::to_string(ncolumns) +
                                " values per vertex row, fewer than ID and position");
  if (rows.size() % ncolumns)
    throw std::invalid_argument("mesh frame: " + std::to_string(rows.size()) +
                                " values are no whole number of rows of " +
                                std::to_string(ncolumns));
  const size_t nrows = rows.size() / ncolumns;
  auto id_of = [&](size_t r) {
    return (long long) rows[r * ncolumns];
  };

  // rows by ID
  std::vector<size_t> order(nrows);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return id_of(a) < id_of(b);
  });
  std::vector<long long> sorted_ids(nrows);
  for (size_t k = 0; k < nrows; k++) sorted_ids[k] = id_of(order[k]);
  for (size_t k = 1; k < nrows; k++)
    if (sorted_ids[k] == sorted_ids[k - 1])
      throw std::invalid_argument("mesh frame: two vertex rows of atom " +
                                  std::to_string(sorted_ids[k]));
  // position in sorted_ids of an ID, -1 if it has no row
  auto rank_of = [&](long long id) -> long long {
    auto it = std::lower_bound(sorted_ids.begin(), sorted_ids.end(), id);
    return (it == sorted_ids.end() || *it != id) ? -1 : (long long) (it - sorted_ids.begin());
  };

  // the triangles whose vertices all have rows, in frame order
  std::vector<FrameTriangle> kept;
  for (const FrameTriangle &t : triangles)
    if (rank_of(t.v[0]) >= 0 && rank_of(t.v[1]) >= 0 && rank_of(t.v[2]) >= 0) kept.push_back(t);
  std::sort(kept.begin(), kept.end(), triangle_before);

  // the vertices they use, numbered in ID order
  std::vector<int> number(nrows, -1);
  for (const FrameTriangle &t : kept)
    for (long long id : t.v) number[rank_of(id)] = 0;
  MeshFrame frame;
  frame.nfields = ncolumns - kFrameRowHead;
  int nvertex = 0;
  for (size_t k = 0; k < nrows; k++) {
    if (number[k] < 0) continue;
    number[k] = nvertex++;
    const double *row = &rows[order[k] * ncolumns];
    frame.ids.push_back(sorted_ids[k]);
    frame.x.insert(frame.x.end(), row + 1, row + kFrameRowHead);
    frame.fields.insert(frame.fields.end(), row + kFrameRowHead, row + ncolumns);
  }
  for (const FrameTriangle &t : kept) {
    frame.triangles.push_back(
        {number[rank_of(t.v[0])], number[rank_of(t.v[1])], number[rank_of(t.v[2])]});
    frame.mesh.push_back(t.mesh);
  }
  return frame;
}

void join_pieces(MeshFrame &frame, const BoxPeriods &box)
{
  const int nv = (int) frame.ids.size();
  std::vector<std::vector<int>> next(nv);    // the vertices each shares an edge with
  for (const auto &t : frame.triangles)
    for (int c = 0; c < 3; c++) {
      next[t[c]].push_back(t[(c + 1) % 3]);
      next[t[(c + 1) % 3]].push_back(t[c]);
    }
  for (auto &n : next) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  const double *edge[3] = {box.a, box.b, box.c};
  std::vector<char> placed(nv, 0);
  std::vector<int> queue;
  for (int root = 0; root < nv; root++) {
    if (placed[root]) continue;
    placed[root] = 1;
    queue.assign(1, root);
    for (size_t q = 0; q < queue.size(); q++) {
      const int u = queue[q];
      for (int v : next[u]) {
        if (placed[v]) continue;
        placed[v] = 1;
        queue.push_back(v);
        double *xv = &frame.x[3 * v];
        const double *xu = &frame.x[3 * u];
        const double d[3] = {xv[0] - xu[0], xv[1] - xu[1], xv[2] - xu[2]};
        // box fractions f of d (d = f0 a + f1 b + f2 c; the edge matrix is upper triangular)
        double f[3];
        f[2] = d[2] / box.c[2];
        f[1] = (d[1] - box.c[1] * f[2]) / box.b[1];
        f[0] = (d[0] - box.b[0] * f[1] - box.c[0] * f[2]) / box.a[0];
        double n[3];
        bool moves = false;
        for (int k = 0; k < 3; k++) {
          n[k] = box.periodic[k] ? std::round(f[k]) : 0.0;
          moves = moves || n[k] != 0.0;
        }
        if (!moves) continue;
        for (int k = 0; k < 3; k++)
          for (int dim = 0; dim < 3; dim++) xv[dim] -= n[k] * edge[k][dim];
      }
    }
  }
}

}    // namespace PeriSISSM
