// A small contact scene for the candidate tests: two triangulated square sheets (n x n vertices,
// spacing h, each square cut along a diagonal) facing each other across a gap, the second
// shifted sideways so that its vertices do not lie above the first's, plus a few volumetric
// particles between them. All atoms are owned (no ghosts), IDs are 1-based in a shuffled order,
// and the neighbor list is the full brute-force list within a cutoff. rows_of(): positions as
// the double ** the core takes.

#ifndef PERISISSM_CONTACT_SCENE_H
#define PERISISSM_CONTACT_SCENE_H

#include "contact/candidates.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace PeriSISSMContactTest {

struct Scene {
  std::vector<std::array<double, 3>> pos;
  std::vector<double *> rows;    // pos as double **
  std::vector<std::int64_t> tag;
  std::vector<PeriSISSM::ContactRole> role;
  std::vector<std::array<int, 3>> triangles;    // local indices
  // the neighbor list
  std::vector<int> ilist, numneigh, flat;
  std::vector<int *> firstneigh;

  int n() const { return (int) pos.size(); }

  void add(double x, double y, double z, PeriSISSM::ContactRole r)
  {
    pos.push_back({x, y, z});
    role.push_back(r);
  }

  // sheet of n x n vertices at height z, shifted by (sx, sy)
  void sheet(int n, double h, double z, double sx, double sy)
  {
    const int base = (int) pos.size();
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++)
        add(sx + i * h, sy + j * h, z, PeriSISSM::ContactRole::kMeshVertex);
    for (int j = 0; j + 1 < n; j++)
      for (int i = 0; i + 1 < n; i++) {
        const int a = base + j * n + i, b = a + 1, c = a + n, d = a + n + 1;
        triangles.push_back({a, b, d});
        triangles.push_back({a, d, c});
      }
  }

  // IDs: a seeded permutation of 1 .. n; the rows; the full list within cutoff
  void finish(double cutoff, unsigned seed)
  {
    tag.resize(n());
    std::iota(tag.begin(), tag.end(), 1);
    std::mt19937_64 rng(seed);
    std::shuffle(tag.begin(), tag.end(), rng);
    rows.clear();
    for (auto &p : pos) rows.push_back(p.data());
    ilist.clear();
    numneigh.assign(n(), 0);
    flat.clear();
    std::vector<int> start;
    for (int i = 0; i < n(); i++) {
      ilist.push_back(i);
      start.push_back((int) flat.size());
      for (int j = 0; j < n(); j++) {
        if (j == i) continue;
        double r2 = 0.0;
        for (int d = 0; d < 3; d++) r2 += (pos[i][d] - pos[j][d]) * (pos[i][d] - pos[j][d]);
        if (r2 < cutoff * cutoff) {
          flat.push_back(j);
          numneigh[i]++;
        }
      }
    }
    firstneigh.clear();
    for (int i = 0; i < n(); i++) firstneigh.push_back(flat.data() + start[i]);
  }

  PeriSISSM::ContactAtoms atoms() const
  {
    PeriSISSM::ContactAtoms a;
    a.nlocal = a.nall = n();
    a.x = rows.data();
    a.tag = tag.data();
    a.role = role.data();
    a.triangles = [this](int i, std::vector<std::array<int, 2>> &others) {
      for (const auto &t : triangles)
        for (int k = 0; k < 3; k++)
          if (t[k] == i) others.push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    };
    return a;
  }

  PeriSISSM::NeighborView list() const
  {
    PeriSISSM::NeighborView v;
    v.inum = n();
    v.ilist = ilist.data();
    v.numneigh = numneigh.data();
    v.firstneigh = firstneigh.data();
    return v;
  }
};

// positions as rows (double **)
inline std::vector<double *> rows_of(std::vector<std::array<double, 3>> &p)
{
  std::vector<double *> r;
  for (auto &q : p) r.push_back(q.data());
  return r;
}

// two 4 x 4 sheets of unit spacing, the second at height gap shifted by (0.4, 0.3), and two
// particles between them at height z (the second at (1.6, y2)); the list within cutoff, the IDs
// shuffled by seed
inline Scene facing_sheets(double gap, double z, double y2, double cutoff, unsigned seed)
{
  Scene s;
  s.sheet(4, 1.0, 0.0, 0.0, 0.0);
  s.sheet(4, 1.0, gap, 0.4, 0.3);
  s.add(1.5, 1.5, z, PeriSISSM::ContactRole::kParticle);
  s.add(1.6, y2, z, PeriSISSM::ContactRole::kParticle);
  s.finish(cutoff, seed);
  return s;
}

}    // namespace PeriSISSMContactTest

#endif
