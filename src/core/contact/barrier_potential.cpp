#include "contact/barrier_potential.h"

#include <algorithm>
#include <cstdio>

using Eigen::Vector3d;

namespace PeriSISSM {

std::string too_close_error(const Candidate &c, double distance, double dmin)
{
  std::string atoms = std::to_string(c.tag[0]);
  for (int k = 1; k < c.nv(); k++) atoms += " " + std::to_string(c.tag[k]);
  char numbers[96];
  std::snprintf(numbers, sizeof(numbers), "%.6g apart, not more than dmin = %.6g", distance, dmin);
  return std::string("the ") + c.stencil().name() + " pair of atoms " + atoms + " is " + numbers +
      ": the barrier is infinite there (the primitives came through the barrier: use a larger "
      "kappa, a smaller time step or a larger dhat)";
}

BarrierTally barrier_forces(const std::vector<Candidate> &candidates,
                            const CandidateDistances &distances, const double *const *x,
                            const double *volume, const BarrierParameters &prm, double mindist,
                            double **f, std::vector<int> *active)
{
  const double range = prm.dmin + prm.dhat;
  BarrierTally t;
  t.mindist = mindist;
  t.ncandidates = distances.counted();
  if (active) active->clear();
  // (the far pairs are beyond the range and the smallest distance: candidate_distances.h)
  for (int ic : distances.near()) {
    const Candidate &c = candidates[ic];
    const double d = distances[ic];
    t.mindist = std::min(t.mindist, d);
    if (!(d < range)) continue;
    if (!(d > prm.dmin)) {
      t.too_close = (long) ic;
      return t;
    }
    if (active) active->push_back(ic);
    const int nv = c.nv();
    Vector3d y[4];
    c.gather(x, y);
    Vector12d g;
    // (a pair within the range is exact: its squared distance is known)
    const double E = c.stencil().barrier_energy_gradient(y, c.eps, distances.squared(ic), prm, g);
    if (c.counts) {
      t.nactive[(int) c.type]++;
      t.energy_pairs += E;
    }
    // each owned vertex's share of the energy: E / nv (1 / nv exact: 0.25 or 0.5)
    const double share = 1.0 / nv;
    for (int k = 0; k < nv; k++) {
      const int i = c.own[k];
      if (i < 0) continue;
      const double vi = volume[i];
      for (int dim = 0; dim < 3; dim++) f[i][dim] -= g[3 * k + dim] / vi;
      t.energy_density += share * E / vi;
    }
  }
  return t;
}

void barrier_blocks(const std::vector<Candidate> &candidates, const std::vector<int> &active,
                    const double *const *x, const double *volume, const BarrierParameters &prm,
                    double **block)
{
  for (int ic : active) {
    const Candidate &c = candidates[ic];
    Vector3d y[4];
    c.gather(x, y);
    add_diagonal_blocks(c.stencil().barrier_hessian(y, c.eps, prm, true), c.nv(), c.own, volume,
                        block);
  }
}

void add_diagonal_blocks(const Matrix12d &H, int nv, const int *own, const double *volume,
                         double **block)
{
  for (int k = 0; k < nv; k++) {
    const int i = own[k];
    if (i < 0) continue;
    const double w = 1.0 / volume[i];
    const int o = 3 * k;
    block[i][0] += w * H(o, o);
    block[i][1] += w * H(o + 1, o + 1);
    block[i][2] += w * H(o + 2, o + 2);
    block[i][3] += w * H(o, o + 1);
    block[i][4] += w * H(o, o + 2);
    block[i][5] += w * H(o + 1, o + 2);
  }
}

}    // namespace PeriSISSM
