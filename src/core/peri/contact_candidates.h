// The candidate pairs of short-range contact (contact.h's ContactCandidates) chosen from a
// neighbor list: for each listed atom i, its neighbors j with |x_i - x_j| < rc, in the list's
// order (ContactShortList); and when they are chosen, with which margin (ContactFollower, by the
// rules of contact/motion_tracker.h). LAMMPS-free.

#ifndef PERISISSM_PERI_CONTACT_CANDIDATES_H
#define PERISISSM_PERI_CONTACT_CANDIDATES_H

#include "contact/motion_tracker.h"
#include "peri/contact.h"

#include <cstdint>
#include <string>
#include <vector>

namespace PeriSISSM {

struct ContactShortList {
  int inum = -1;             // the atoms of the list it was chosen from (-1: never chosen)
  std::vector<int> first;    // inum + 1 offsets into neigh
  std::vector<int> neigh;    // the candidates of ilist[ii]: neigh[first[ii] .. first[ii+1] - 1]

  // Inputs: a neighbor list in LAMMPS's layout (the atoms ilist[0 .. inum - 1], the neighbors
  // of atom i firstneigh[i][0 .. numneigh[i] - 1], each masked with neighmask), positions x
  // (local indices) and rc. Output: first, neigh and inum of the pairs closer than rc.
  void choose(int list_inum, const int *ilist, const int *numneigh, int *const *firstneigh,
              int neighmask, const double *const *x, double rc);
  bool chosen() const { return inum >= 0; }
};

// When the candidates are chosen and with which margin m (the list holds the pairs within
// reach + m). Not followed, m is the skin, which covers all motion until the next neighbor list
// build. Followed (tracked: an implicit integrator's iterates; or explicit runs where
// MotionTracker::followable()), m is skin/4 and the pairs are chosen again once an atom has moved
// m/2 from where they were chosen, complete while MotionTracker::reachable() from the build.
// Positions are those of owned and ghost atoms (every candidate pair has both on the rank; ghost
// indices hold between neighbor list builds); the motions of owned atoms that the caller reduces
// over its ranks come from local_moves2().
class ContactFollower {
 public:
  ContactShortList list;
  MotionTracker at_build, at_choice;    // positions at the build and at the choice (followed)
  double reach = 0.0;      // the largest contact range (1.35 x the largest particle size)
  double horizon = 0.0;    // the smallest horizon of the type pairs with contact

  // follow an implicit integrator's iterates (or not: the positions are forgotten); whether
  // explicit runs follow is decided again at the next build
  void track(bool on);
  bool tracked() const { return tracked_; }
  bool followed() const { return tracked_ || explicit_; }
  bool followed_explicit() const { return explicit_; }
  double margin() const { return margin_; }

  // after a neighbor list build with positions x of nall atoms: decides whether an explicit run
  // follows, keeps x as the build's when followed; returns the margin to choose with
  double margin_at_build(const double *const *x, int nall, double skin);
  // list.choose() of the pairs within reach + margin from the neighbor list of build stamp
  // `build` (positions kept as the choice's when followed)
  void choose(int inum, const int *ilist, const int *numneigh, int *const *firstneigh,
              int neighmask, const double *const *x, int nall, double margin, std::int64_t build);
  // the pairs chosen, for contact_pass(); ilist: the neighbor list's atoms
  ContactCandidates candidates(const int *ilist) const
  {
    return {list.inum, ilist, list.first.data(), list.neigh.data()};
  }
  // whether the pairs were chosen from the neighbor list of build stamp `build`
  bool current(std::int64_t build) const { return list.chosen() && build_ == build; }
  // the bytes of the list and the positions kept
  double bytes() const;
  // explicit runs (false unless followed_explicit()): whether an atom has moved margin/2 from the
  // choice; then (in margin) the margin for the new choice, MotionTracker::reachable_margin()
  // of the move from the build
  bool explicit_rechoice(const double *const *x, int nall, double skin, double &margin) const;
  // the squared largest moves of owned atoms i < nlocal from the choice (moves2[0]) and from the
  // build (moves2[1], its atom in farthest, -1: none)
  void local_moves2(const double *const *x, int nlocal, double moves2[2], int &farthest) const;
  // whether the choice with margin skin/4 is complete after moves up to `moved` from the build
  bool reachable(double moved, double skin) const;
  // how an implicit (sub-)step should start when the atoms have moved by up to `moved` from the
  // build (all ranks): 0 from these candidates (moved <= MotionTracker::request_distance()), 1
  // from a new neighbor list, 2 the candidates cannot be complete here (not reachable())
  int build_wanted(double moved, double skin) const;
  // an implicit iterate with largest moves from_choice and from_build (over all ranks): -1 the
  // candidates cannot be complete, 0 they are, 1 choose again with MotionTracker::follow_margin()
  int after_motion(double from_choice, double from_build, double skin) const;
  // the error of an implicit step at `step` that moved atom `atom` by `moved` from the build,
  // beyond reachable(); cause: why the step went on (appended when not empty)
  std::string too_far(std::int64_t step, std::int64_t atom, double moved, double skin,
                      const std::string &cause) const;

 private:
  bool tracked_ = false, explicit_ = false;
  double margin_ = 0.0;
  std::int64_t build_ = -1;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_CONTACT_CANDIDATES_H
