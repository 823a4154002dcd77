#include "contact/path_limit.h"

#include <algorithm>
#include <cmath>

using Eigen::Vector3d;

namespace PeriSISSM {

namespace {

  // the longest move of the n atoms from xref to x
  double longest_move(const double *const *xref, const double *const *x, int n)
  {
    double most2 = 0.0;
    for (int i = 0; i < n; i++) {
      const double dx = x[i][0] - xref[i][0], dy = x[i][1] - xref[i][1], dz = x[i][2] - xref[i][2];
      most2 = std::max(most2, dx * dx + dy * dy + dz * dz);
    }
    return std::sqrt(most2);
  }

  // how fast a pair's gap can close: ccd.h's rate l (the largest move of a point of each
  // primitive relative to the pair's mean move, summed), or closing()'s without the mean when
  // that is smaller; both bound the distance's loss over a straight move
  double closing_rate(StencilType type, int nv, const Vector3d *dy)
  {
    Vector3d mean = Vector3d::Zero();
    double len[4], rel[4];
    for (int k = 0; k < nv; k++) {
      mean += dy[k];
      len[k] = dy[k].norm();
    }
    mean /= nv;
    for (int k = 0; k < nv; k++) rel[k] = (dy[k] - mean).norm();
    return std::min(closing(type, len), closing(type, rel));
  }

}    // namespace

double path_limit(const std::vector<Candidate> &candidates, const double *const *xref,
                  const double *const *x, int n, double dmin, CandidateDistances *known,
                  double t_max)
{
  const bool gaps = known && known->valid();
  double t_pairs = t_max;
  CcdOptions opt;
  opt.dmin = dmin;
  const auto limit = [&](std::size_t ic) {
    const Candidate &c = candidates[ic];
    const CollisionStencil &stencil = c.stencil();
    Vector3d y[4], dy[4];
    bool moved = false;
    for (int k = 0; k < c.nv(); k++) {
      const double *a = xref[c.v[k]], *b = x[c.v[k]];
      y[k] = Vector3d(a[0], a[1], a[2]);
      dy[k] = Vector3d(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
      moved = moved || dy[k].squaredNorm() > 0.0;
    }
    if (!moved) return;
    if (gaps) {
      // (a lower bound that does not suffice is replaced by the distance: the same pairs are
      // skipped as with the distances, and the move is the same)
      const double most = closing_rate(c.type, c.nv(), dy) * t_pairs;
      if (most <= (1.0 - opt.s) * ((*known)[ic] - dmin)) return;
      if (!known->exact(ic)) {
        const double D = stencil.distance2(y);
        const double d = std::sqrt(D);
        known->set_exact(ic, D);
        if (most <= (1.0 - opt.s) * (d - dmin)) return;
      }
    }
    // (a query that reaches ACCD's sub-step cap returns the last safe time: still conservative)
    opt.t_max = t_pairs;
    t_pairs = std::min(t_pairs, stencil.ccd(y, dy, opt));
  };
  if (!gaps) {
    for (std::size_t ic = 0; ic < candidates.size(); ic++) limit(ic);
    return t_pairs;
  }
  // the near pairs one by one; the far ones all at once when no point moves far enough to
  // close the gap they all keep (as each of them would be skipped), else one by one
  for (int ic : known->near()) limit((std::size_t) ic);
  if (2.0 * longest_move(xref, x, n) * t_pairs <= (1.0 - opt.s) * (known->far_bound() - dmin))
    return t_pairs;
  for (std::size_t ic = 0; ic < candidates.size(); ic++)
    if (known->far(ic)) limit(ic);
  return t_pairs;
}

bool move_within_gaps(const double *const *xref, const double *const *x, int n, double dmin,
                      const CandidateDistances &known)
{
  if (!known.valid()) return false;
  return 2.0 * longest_move(xref, x, n) <= (1.0 - CcdOptions().s) * known.gap_bound(dmin);
}

void scale_move(const double *const *xref, double **x, int n, const int *mask, int groupbit,
                double t)
{
  for (int i = 0; i < n; i++)
    if (mask[i] & groupbit)
      for (int k = 0; k < 3; k++) x[i][k] = xref[i][k] + t * (x[i][k] - xref[i][k]);
}

}    // namespace PeriSISSM
