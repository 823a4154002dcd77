// Additive continuous collision detection (see ccd.h).

#include "contact/ccd.h"

#include "contact/distance.h"

#include <algorithm>
#include <array>

namespace PeriSISSM {

using Eigen::Vector3d;

namespace {

  // ACCD over K points, the first KA of them primitive A, the rest primitive B; distance(x) is the
  // distance of the two primitives at positions x.
  //   The positions at time t are recomputed from the start, x_i + t dx_i, rather than accumulated,
  // so that round-off does not drift over many sub-steps. Only relative motion matters, so the mean
  // displacement is removed first (it also makes l as small as the bound allows).
  template <int K, int KA, class Distance>
  double additive_ccd(const std::array<Vector3d, K> &x, std::array<Vector3d, K> dx,
                      Distance distance, const CcdOptions &opt, CcdReport *report)
  {
    CcdReport local;
    CcdReport &r = report ? *report : local;
    r = CcdReport();

    Vector3d mean = Vector3d::Zero();
    for (const Vector3d &d : dx) mean += d;
    mean /= K;
    double la = 0.0, lb = 0.0;
    for (int i = 0; i < K; i++) {
      dx[i] -= mean;
      if (i < KA)
        la = std::max(la, dx[i].norm());
      else
        lb = std::max(lb, dx[i].norm());
    }
    const double l = la + lb;

    const double g0 = distance(x) - opt.dmin;
    if (!(g0 > 0.0)) {
      r.initially_close = true;
      return 0.0;
    }
    if (!(l > 0.0)) return opt.t_max;    // no relative motion: the distance stays g0 + dmin

    const double keep = opt.s * g0;    // stop before the gap falls below this
    double t = 0.0;
    double step = (1.0 - opt.s) * g0 / l;
    // (a first sub-step that reaches the end needs no look at its distance: the loop below
    // would return t_max after it whatever the distance)
    if (step >= opt.t_max) return opt.t_max;
    std::array<Vector3d, K> y;
    while (r.iterations < opt.max_iterations) {
      r.iterations++;
      for (int i = 0; i < K; i++) y[i] = x[i] + (t + step) * dx[i];
      const double g = distance(y) - opt.dmin;
      if (t > 0.0 && g < keep) return t;
      t += step;
      if (t >= opt.t_max) return opt.t_max;
      step = 0.9 * g / l;
    }
    r.capped = true;
    return t;
  }

}    // namespace

double point_triangle_ccd(const Vector3d &p, const Vector3d &t0, const Vector3d &t1,
                          const Vector3d &t2, const Vector3d &dp, const Vector3d &dt0,
                          const Vector3d &dt1, const Vector3d &dt2, const CcdOptions &opt,
                          CcdReport *report)
{
  auto distance = [](const std::array<Vector3d, 4> &y) {
    return point_triangle_distance(y[0], y[1], y[2], y[3]);
  };
  return additive_ccd<4, 1>({p, t0, t1, t2}, {dp, dt0, dt1, dt2}, distance, opt, report);
}

double edge_edge_ccd(const Vector3d &a0, const Vector3d &a1, const Vector3d &b0, const Vector3d &b1,
                     const Vector3d &da0, const Vector3d &da1, const Vector3d &db0,
                     const Vector3d &db1, const CcdOptions &opt, CcdReport *report)
{
  auto distance = [](const std::array<Vector3d, 4> &y) {
    return edge_edge_distance(y[0], y[1], y[2], y[3]);
  };
  return additive_ccd<4, 2>({a0, a1, b0, b1}, {da0, da1, db0, db1}, distance, opt, report);
}

double point_point_ccd(const Vector3d &p, const Vector3d &q, const Vector3d &dp, const Vector3d &dq,
                       const CcdOptions &opt, CcdReport *report)
{
  auto distance = [](const std::array<Vector3d, 2> &y) {
    return (y[0] - y[1]).norm();
  };
  return additive_ccd<2, 1>({p, q}, {dp, dq}, distance, opt, report);
}

}    // namespace PeriSISSM
