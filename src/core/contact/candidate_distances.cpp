#include "contact/candidate_distances.h"

#include <algorithm>
#include <cmath>

using Eigen::Vector3d;

namespace PeriSISSM {

void CandidateDistances::evaluate(const std::vector<Candidate> &candidates, const double *const *x,
                                  int nall, std::int64_t generation, double range, double nearest)
{
  const bool bounded = xlast_generation == generation && distance.size() == candidates.size() &&
      xlast.size() >= 3 * (std::size_t) nall;
  std::vector<double> moved;
  if (bounded) {
    moved.resize(nall);
    for (int i = 0; i < nall; i++) {
      const double *o = &xlast[3 * i];
      const double dx = x[i][0] - o[0], dy = x[i][1] - o[1], dz = x[i][2] - o[2];
      moved[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  distance.resize(candidates.size());
  exact_.assign(candidates.size(), 1);
  smallest_ = HUGE_VAL;
  for (std::size_t ic = 0; ic < candidates.size(); ic++) {
    const Candidate &c = candidates[ic];
    if (bounded) {
      double len[4];
      for (int k = 0; k < c.nv(); k++) len[k] = moved[c.v[k]];
      const double bound = distance[ic] - closing(c.type, len);
      if (bound >= range && bound >= nearest) {
        distance[ic] = bound;
        exact_[ic] = 0;
        smallest_ = std::min(smallest_, bound);
        continue;
      }
    }
    Vector3d y[4];
    c.gather(x, y);
    distance[ic] = std::sqrt(c.stencil().distance2(y));
    nearest = std::min(nearest, distance[ic]);
    smallest_ = std::min(smallest_, distance[ic]);
  }
  valid_ = true;
  xlast.resize(3 * (std::size_t) nall);
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) xlast[3 * i + d] = x[i][d];
  xlast_generation = generation;
}

double CandidateDistances::smallest_gap(double dmin) const
{
  double gap = HUGE_VAL;
  for (double d : distance) gap = std::min(gap, d - dmin);
  return gap;
}

}    // namespace PeriSISSM
