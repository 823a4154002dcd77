// How far atoms have moved since candidate pairs were last chosen. A contact model that chooses
// its pairs at a neighbor list build, keeping those closer than r + skin, finds every pair that
// can come within r while no atom has moved more than skin/2 from where it was then (two atoms
// close by at most twice that). The tracker keeps the positions of that build and answers:
// the largest move since (error beyond error_distance(), a new build wanted beyond
// request_distance() inside a step and beyond rebuild_distance() at a step's end, so that each
// step may still move the atoms by 3/8 of the skin), and how far along a straight move an atom
// stays within a given distance of its build position (reach_fraction()).
//
// A contact model that chooses its pairs again between neighbor list builds (from a list of
// cutoff horizon + skin built at x_n, the pairs within reach + m at the current positions) keeps
// one tracker for x_n and one for where it chose: the choice is complete while no atom has
// moved m/2 from there and reach + m + 2 max|x - x_n| <= horizon + skin (reachable()).
//
// Use: record() at every build; largest_move2() at every force evaluation (the caller takes the
// maximum over its ranks). Indices are local (owned atoms, or owned and ghost atoms when the
// caller records those); they hold until the next build. LAMMPS-free.

#ifndef PERISISSM_CONTACT_MOTION_TRACKER_H
#define PERISISSM_CONTACT_MOTION_TRACKER_H

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace PeriSISSM {

class MotionTracker {
 public:
  // the skin thresholds: the candidates may be incomplete beyond skin/2 (an error), a build is
  // asked for beyond skin/4 inside a step and wanted beyond skin/8 at a step's end
  static double error_distance(double skin) { return 0.5 * skin; }
  static double request_distance(double skin) { return 0.25 * skin; }
  static double rebuild_distance(double skin) { return 0.125 * skin; }
  // At the end of a step whose largest move predicts the next step's (predicted: that move
  // scaled to the next step's length): a build is wanted once an atom has moved so far that
  // the next step has less than 1.5 predicted left before skin/2, and in any case beyond 3/8 of
  // the skin. Where the motion is steady this builds a list every few steps instead of at
  // every step that moves an atom skin/8, and a step that then needs more than the reach is
  // redone as sub-steps as before.
  static bool rebuild_due(double moved, double predicted, double skin)
  {
    return moved > std::min(0.375 * skin, 0.5 * skin - 1.5 * predicted);
  }
  // the errors of a contact model for an atom (by ID) that moved `moved` (> error_distance())
  // since the neighbor list build at step `build`, and for an implicit step of `integrator` that
  // needs an atom beyond error_distance(skin) (from: its distance at the start of the move)
  static std::string moved_error(std::int64_t atom, double moved, std::int64_t build);
  static std::string reach_error(const std::string &integrator, std::int64_t step,
                                 std::int64_t atom, double skin, double from);

  // pairs chosen again between builds: the margin m = skin/4 they are chosen with
  static double follow_margin(double skin) { return 0.25 * skin; }
  // whether pairs chosen within reach + margin from a neighbor list of cutoff horizon + skin are
  // complete when the atoms have moved by up to `moved` from the list's build (false if not
  // finite): reach + margin + 2 moved <= horizon + skin
  static bool reachable(double reach, double margin, double moved, double horizon, double skin)
  {
    return reach + margin + 2.0 * moved <= horizon + skin;
  }
  // the margin for a choice after the atoms moved by `moved` from the list's build: the largest
  // in [0, follow_margin(skin)] that reachable() allows, horizon + skin - reach - 2 moved
  static double reachable_margin(double reach, double moved, double horizon, double skin);
  // whether a run whose neighbor lists keep every move below skin/2 (LAMMPS's own rebuilds) can
  // choose its pairs with follow_margin(skin): reach + skin/4 <= horizon
  static bool followable(double reach, double horizon, double skin)
  {
    return reach + follow_margin(skin) <= horizon;
  }

  // the positions x[0 .. n - 1] at a build
  void record(const double *const *x, int n);
  // the largest squared distance of an atom i < n with (mask[i] & groupbit) (every atom i < n
  // when mask is nullptr) from where it was at the build, and that atom (farthest, -1: none; of
  // equals the first)
  double largest_move2(const double *const *x, int n, const int *mask, int groupbit,
                       int &farthest) const;
  // whether an atom i < n is at least sqrt(limit2) from where it was at the build (stops at the
  // first)
  bool moved_at_least2(const double *const *x, int n, double limit2) const;
  // For atom i on the straight move from xref to x (xref within R of its build position): the
  // largest fraction t in [0, 1] with |xref + t (x - xref) - xbuild| <= R, times (1 - 1e-12);
  // 1 when x is within R too (the segment is inside the ball when both ends are). from: the
  // distance of xref from the build position.
  double reach_fraction(int i, const double *xref, const double *x, double R, double &from) const;

  // The reach of a move over the atoms i < n with (mask[i] & groupbit): the smallest
  // reach_fraction() below 1 (t = 1: no atom leaves the ball), the atom that sets it (-1: none;
  // of equals the one with the smallest tag) and its distance from the build at xref.
  struct Reach {
    double t = 1.0;
    int atom = -1;
    double from = 0.0;
  };
  template <class Tag>
  Reach reach_limit(const double *const *xref, const double *const *x, int n, const int *mask,
                    int groupbit, const Tag *tag, double R) const
  {
    Reach r;
    for (int i = 0; i < n; i++) {
      if (!(mask[i] & groupbit)) continue;
      double from;
      const double t = reach_fraction(i, xref[i], x[i], R, from);
      if (t >= 1.0) continue;
      if (t < r.t || (t == r.t && r.atom >= 0 && tag[i] < tag[r.atom])) {
        r.t = t;
        r.atom = i;
        r.from = from;
      }
    }
    return r;
  }

  // the positions kept (3 per atom); clear() forgets them
  std::size_t size() const { return xbuild.size() / 3; }
  void clear() { xbuild.clear(); }

 private:
  std::vector<double> xbuild;
  // the squared distance of x (atom i) from its build position
  double move2(int i, const double *x) const;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_MOTION_TRACKER_H
