#include "contact/candidate_distances.h"

#include <algorithm>
#include <cmath>

using Eigen::Vector3d;

namespace PeriSISSM {

void CandidateDistances::evaluate(const std::vector<Candidate> &candidates, const double *const *x,
                                  int nall, std::int64_t generation, double range, double nearest,
                                  double margin)
{
  const std::size_t n = candidates.size();
  const double nearest_given = nearest;
  smallest_ = HUGE_VAL;
  const bool same = xlast_generation == generation && distance.size() == n &&
      xlast.size() >= 3 * (std::size_t) nall && xsplit.size() >= 3 * (std::size_t) nall;
  if (!same) {
    // new candidates: every pair exact
    distance.assign(n, 0.0);
    distance2.assign(n, 0.0);
    exact_.assign(n, 1);
    far_.assign(n, 0);
    counted_ = 0;
    for (const Candidate &c : candidates) counted_ += c.counts ? 1 : 0;
    pass(candidates, x, nullptr, false, moved, range, nearest);
    split(candidates, x, nall, range, nearest_given, margin);
  } else {
    // the near pairs, bounded by their points' moves since the last evaluation
    moved.resize(nall);
    double most2 = 0.0;
    for (int i = 0; i < nall; i++) {
      const double *o = &xlast[3 * i], *s = &xsplit[3 * i];
      const double dx = x[i][0] - o[0], dy = x[i][1] - o[1], dz = x[i][2] - o[2];
      moved[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double ex = x[i][0] - s[0], ey = x[i][1] - s[1], ez = x[i][2] - s[2];
      most2 = std::max(most2, ex * ex + ey * ey + ez * ez);
    }
    nearest = pass(candidates, x, &near_, true, moved, range, nearest);
    const double stale = 2.0 * std::sqrt(most2);
    const double bound = far_floor_ - stale;
    if (stale <= margin_ && (smallest_ <= bound || bound >= nearest_given)) {
      stale_ = stale;
      smallest_ = std::min(smallest_, bound);
    } else {
      // the far pairs, bounded by their points' moves since the split; then a new split
      std::vector<int> far;
      for (std::size_t ic = 0; ic < n; ic++)
        if (far_[ic]) far.push_back((int) ic);
      for (int i = 0; i < nall; i++) {
        const double *s = &xsplit[3 * i];
        const double ex = x[i][0] - s[0], ey = x[i][1] - s[1], ez = x[i][2] - s[2];
        moved[i] = std::sqrt(ex * ex + ey * ey + ez * ez);
      }
      pass(candidates, x, &far, true, moved, range, nearest);
      split(candidates, x, nall, range, nearest_given, margin);
    }
  }
  valid_ = true;
  xlast.resize(3 * (std::size_t) nall);
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) xlast[3 * i + d] = x[i][d];
  xlast_generation = generation;
}

double CandidateDistances::pass(const std::vector<Candidate> &candidates, const double *const *x,
                                const std::vector<int> *idx, bool bounded,
                                const std::vector<double> &moved, double range, double nearest)
{
  // (the near pairs' kinds and points from their contiguous copy: 20 bytes a pair, not the 96
  // of a candidate scattered among the far ones)
  const bool near = idx == &near_;
  const std::size_t n = idx ? idx->size() : candidates.size();
  for (std::size_t k = 0; k < n; k++) {
    const std::size_t ic = idx ? (std::size_t) (*idx)[k] : k;
    const StencilType type = near ? near_pairs_[k].type : candidates[ic].type;
    const int *v = near ? near_pairs_[k].v : candidates[ic].v;
    const int nv = type == StencilType::kPointPoint ? 2 : 4;
    far_[ic] = 0;
    if (bounded) {
      double len[4];
      for (int j = 0; j < nv; j++) len[j] = moved[v[j]];
      const double bound = distance[ic] - closing(type, len);
      if (bound >= range && bound >= nearest) {
        distance[ic] = bound;
        exact_[ic] = 0;
        smallest_ = std::min(smallest_, bound);
        continue;
      }
    }
    Vector3d y[4];
    for (int j = 0; j < nv; j++) y[j] = Vector3d(x[v[j]][0], x[v[j]][1], x[v[j]][2]);
    distance2[ic] = CollisionStencil::of(type).distance2(y);
    distance[ic] = std::sqrt(distance2[ic]);
    exact_[ic] = 1;
    nearest = std::min(nearest, distance[ic]);
    smallest_ = std::min(smallest_, distance[ic]);
  }
  return nearest;
}

void CandidateDistances::split(const std::vector<Candidate> &candidates, const double *const *x,
                               int nall, double range, double nearest, double margin)
{
  const double threshold = std::max(range, std::min(smallest_, nearest));
  const double floor = threshold + margin;
  near_.clear();
  near_pairs_.clear();
  bool any_far = false;
  for (std::size_t ic = 0; ic < distance.size(); ic++) {
    far_[ic] = distance[ic] >= floor ? 1 : 0;
    if (far_[ic]) {
      exact_[ic] = 0;
      any_far = true;
    } else {
      near_.push_back((int) ic);
      const Candidate &c = candidates[ic];
      near_pairs_.push_back({c.type, {c.v[0], c.v[1], c.v[2], c.v[3]}});
    }
  }
  far_floor_ = any_far ? floor : HUGE_VAL;
  stale_ = 0.0;
  margin_ = margin;
  xsplit.resize(3 * (std::size_t) nall);
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) xsplit[3 * i + d] = x[i][d];
}

double CandidateDistances::memory_bytes() const
{
  return (double) (distance.capacity() + distance2.capacity() + xlast.capacity() +
                   xsplit.capacity() + moved.capacity()) *
      sizeof(double) +
      (double) (exact_.capacity() + far_.capacity()) + (double) near_.capacity() * sizeof(int) +
      (double) near_pairs_.capacity() * sizeof(NearPair);
}

double CandidateDistances::smallest_gap(double dmin) const
{
  double gap = HUGE_VAL;
  for (std::size_t ic = 0; ic < distance.size(); ic++) gap = std::min(gap, (*this)[ic] - dmin);
  return gap;
}

}    // namespace PeriSISSM
