#include "contact/motion_tracker.h"

#include "linalg/general_format.h"

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

std::string MotionTracker::moved_error(std::int64_t atom, double moved, std::int64_t build)
{
  return "atom " + std::to_string(atom) + " moved " + general_format(moved, 6) +
      " since the last neighbor list build at step " + std::to_string(build) +
      ", more than half the neighbor skin: contact pairs may be missing; let LAMMPS rebuild the "
      "lists when needed (neigh_modify every 1 delay 0 check yes), use a larger skin or a "
      "smaller time step";
}

std::string MotionTracker::reach_error(const std::string &integrator, std::int64_t step,
                                       std::int64_t atom, double skin, double from)
{
  return integrator + " step " + std::to_string(step) + " needs atom " + std::to_string(atom) +
      " to move farther than half the neighbor skin (" + general_format(error_distance(skin), 6) +
      ") from where it was at the last neighbor list build (it was " + general_format(from, 6) +
      " from there at the start of the move): the contact candidates cannot follow a step that "
      "far; use a larger neighbor skin (a step may move the atoms by 3/8 of it at least: the "
      "lists are built again after a step that moved an atom skin/8) or a smaller time step";
}

void MotionTracker::record(const double *const *x, int n)
{
  xbuild.resize(3 * (std::size_t) n);
  for (int i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) xbuild[3 * i + d] = x[i][d];
}

double MotionTracker::move2(int i, const double *x) const
{
  const double *b = &xbuild[3 * i];
  double r2 = 0.0;
  for (int d = 0; d < 3; d++) r2 += (x[d] - b[d]) * (x[d] - b[d]);
  return r2;
}

double MotionTracker::largest_move2(const double *const *x, int n, const int *mask, int groupbit,
                                    int &farthest) const
{
  double most = 0.0;
  farthest = -1;
  for (int i = 0; i < n; i++) {
    if (mask && !(mask[i] & groupbit)) continue;
    const double r2 = move2(i, x[i]);
    if (r2 > most) {
      most = r2;
      farthest = i;
    }
  }
  return most;
}

bool MotionTracker::moved_at_least2(const double *const *x, int n, double limit2) const
{
  for (int i = 0; i < n; i++)
    if (move2(i, x[i]) >= limit2) return true;
  return false;
}

double MotionTracker::reachable_margin(double reach, double moved, double horizon, double skin)
{
  const double room = horizon + skin - reach - 2.0 * moved;
  return std::max(0.0, std::min(follow_margin(skin), room));
}

// |a + t d|^2 = R^2 (a = xref - xbuild, d = x - xref) for the root in [0, 1] (|a| <= R)
double MotionTracker::reach_fraction(int i, const double *xref, const double *x, double R,
                                     double &from) const
{
  const double *b = &xbuild[3 * i];
  double a2 = 0.0, ad = 0.0, d2 = 0.0, e2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double a = xref[k] - b[k], d = x[k] - xref[k];
    a2 += a * a;
    ad += a * d;
    d2 += d * d;
    e2 += (a + d) * (a + d);
  }
  from = std::sqrt(a2);
  if (e2 <= R * R) return 1.0;
  const double disc = std::max(0.0, ad * ad - d2 * (a2 - R * R));
  return std::max(0.0, (-ad + std::sqrt(disc)) / d2) * (1.0 - 1.0e-12);
}

}    // namespace PeriSISSM
