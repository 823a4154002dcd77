#include "peri/contact_candidates.h"

#include <cmath>
#include <cstdio>

namespace PeriSISSM {

void ContactShortList::choose(int list_inum, const int *ilist, const int *numneigh,
                              int *const *firstneigh, int neighmask, const double *const *x,
                              double rc)
{
  const double rcsq = rc * rc;
  first.resize((std::size_t) list_inum + 1);
  neigh.clear();
  for (int ii = 0; ii < list_inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    first[ii] = (int) neigh.size();
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & neighmask;
      const double dx = x[i][0] - x[j][0];
      const double dy = x[i][1] - x[j][1];
      const double dz = x[i][2] - x[j][2];
      if (dx * dx + dy * dy + dz * dz < rcsq) neigh.push_back(j);
    }
  }
  first[list_inum] = (int) neigh.size();
  inum = list_inum;
}

}    // namespace PeriSISSM

namespace PeriSISSM {

void ContactFollower::track(bool on)
{
  tracked_ = on;
  explicit_ = false;
  if (!tracked_) {
    at_build.clear();
    at_choice.clear();
  }
}

double ContactFollower::margin_at_build(const double *const *x, int nall, double skin)
{
  explicit_ = !tracked_ && MotionTracker::followable(reach, horizon, skin);
  if (!followed()) return skin;
  at_build.record(x, nall);
  return MotionTracker::follow_margin(skin);
}

void ContactFollower::choose(int inum, const int *ilist, const int *numneigh,
                             int *const *firstneigh, int neighmask, const double *const *x,
                             int nall, double margin, std::int64_t build)
{
  margin_ = margin;
  build_ = build;
  list.choose(inum, ilist, numneigh, firstneigh, neighmask, x, reach + margin);
  if (followed()) at_choice.record(x, nall);
}

double ContactFollower::bytes() const
{
  return (double) (list.first.capacity() + list.neigh.capacity()) * sizeof(int) +
      3.0 * (double) (at_build.size() + at_choice.size()) * sizeof(double);
}

bool ContactFollower::explicit_rechoice(const double *const *x, int nall, double skin,
                                        double &margin) const
{
  if (!explicit_ || !at_choice.moved_at_least2(x, nall, 0.25 * margin_ * margin_)) return false;
  int farthest;
  const double moved = at_build.largest_move2(x, nall, nullptr, 0, farthest);
  margin = MotionTracker::reachable_margin(reach, std::sqrt(moved), horizon, skin);
  return true;
}

void ContactFollower::local_moves2(const double *const *x, int nlocal, double moves2[2],
                                   int &farthest) const
{
  int ifar;
  moves2[0] = at_choice.largest_move2(x, nlocal, nullptr, 0, ifar);
  moves2[1] = at_build.largest_move2(x, nlocal, nullptr, 0, farthest);
}

bool ContactFollower::reachable(double moved, double skin) const
{
  return MotionTracker::reachable(reach, MotionTracker::follow_margin(skin), moved, horizon, skin);
}

int ContactFollower::build_wanted(double moved, double skin) const
{
  if (!reachable(moved, skin)) return 2;
  return moved > MotionTracker::request_distance(skin) ? 1 : 0;
}

int ContactFollower::after_motion(double from_choice, double from_build, double skin) const
{
  if (!reachable(from_build, skin)) return -1;
  return from_choice < 0.5 * margin_ ? 0 : 1;
}

std::string ContactFollower::too_far(std::int64_t step, std::int64_t atom, double moved,
                                     double skin, const std::string &cause) const
{
  char buf[1024];
  std::snprintf(buf, sizeof(buf),
                "Pair peri/nosb: the implicit step %lld moved atom %lld by %.4g from where it was "
                "at the last neighbor list build, farther than short-range contact can follow "
                "inside one step with neighbor skin %.4g (a step may move atoms by (horizon - "
                "1.35 x particle size) / 2 + skin / 4 = %.4g)%s; use a smaller time step, a "
                "neighbor skin of at least %.4g, or turn contact off for these types "
                "(pair_coeff ... contact no)",
                (long long) step, (long long) atom, moved, skin,
                0.5 * (horizon - reach) + 0.25 * skin, cause.empty() ? "" : ("; " + cause).c_str(),
                2.0 * (2.0 * moved + reach - horizon));
  return buf;
}

}    // namespace PeriSISSM
