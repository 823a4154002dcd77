#include "contact/adaptive_stiffness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

using Eigen::Vector3d;

namespace PeriSISSM {

void AdaptiveStiffness::set_scene(double bbox_diagonal, double mean_mass, double dhat)
{
  bbox_diagonal_ = bbox_diagonal;
  mean_mass_ = mean_mass;
  dhat_ = dhat;
  kappa_min = initial_barrier_stiffness(bbox_diagonal, dhat, mean_mass, 0.0, 0.0, kappa_max);
  kappa_ip_ = kappa_min;
}

void AdaptiveStiffness::restore(double kappa_ip)
{
  kappa_ip_ = std::min(kappa_max, std::max(kappa_min, kappa_ip));
}

double AdaptiveStiffness::at_iterate(double min_gap)
{
  const double k =
      update_barrier_stiffness(prev_min_gap, min_gap, kappa_max, kappa_ip_, bbox_diagonal_);
  prev_min_gap = min_gap;
  return k;
}

void SceneExtent::add(const double *x, double m)
{
  for (int d = 0; d < 3; d++) {
    lo[d] = std::min(lo[d], x[d]);
    hi[d] = std::max(hi[d], x[d]);
  }
  mass[0] += m;
  mass[1] += 1.0;
}

double SceneExtent::diagonal() const
{
  double diag2 = 0.0;
  for (int d = 0; d < 3; d++) diag2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  return std::sqrt(diag2);
}

std::string SceneExtent::error() const
{
  if (diagonal() > 0.0 && mean_mass() > 0.0) return "";
  char numbers[64];
  std::snprintf(numbers, sizeof(numbers), "%.6g, the mean mass %.6g", diagonal(), mean_mass());
  return std::string("kappa auto needs a group of atoms with mass that spans a box (its "
                     "diagonal ") +
      numbers + ")";
}

double AdaptiveStiffness::balanced(double res_dot_grad, double grad2) const
{
  double kmax;
  return initial_barrier_stiffness(bbox_diagonal_, dhat_, mean_mass_,
                                   -res_dot_grad - kappa_ip_ * grad2, grad2, kmax);
}

BalanceSums balance_sums(const std::vector<Candidate> &candidates,
                         const CandidateDistances &distances, const double *const *x,
                         const double *const *res, const double *volume, const int *mask,
                         int groupbit, int nlocal, double dhat, double dmin)
{
  const BarrierParameters unit{1.0, dhat, dmin};
  const double range = dmin + dhat;
  std::vector<double> grad(3 * (std::size_t) nlocal, 0.0);
  BalanceSums s;
  for (int ic : distances.near()) {
    const Candidate &c = candidates[ic];
    if (!(distances.valid() && distances[ic] < range)) continue;
    Vector3d y[4];
    c.gather(x, y);
    const Vector12d g = c.stencil().barrier_gradient(y, c.eps, unit);
    for (int k = 0; k < c.nv(); k++) {
      const int i = c.own[k];
      if (i < 0 || !(mask[i] & groupbit)) continue;
      s.active = true;
      for (int d = 0; d < 3; d++) grad[3 * i + d] += g[3 * k + d];
    }
  }
  if (s.active)
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      for (int d = 0; d < 3; d++) {
        s.res_dot_grad += res[i][d] * volume[i] * grad[3 * i + d];
        s.grad2 += grad[3 * i + d] * grad[3 * i + d];
      }
    }
  return s;
}

}    // namespace PeriSISSM
