// The distances of a set of candidate pairs (candidates.h) at the last force evaluation, kept
// for the next evaluation and for the path limit (path_limit.h).
//
// Bounds. Since the last evaluation of the same candidates a pair's distance shrank at most by
// how far a point of each primitive moved (closing(), stencil.h): when that lower bound is
// beyond the barrier's range and not below the smallest distance found so far, the pair neither
// acts nor is the nearest, and the bound stands in for the distance (exact(ic) is then false;
// the path limit takes it as a smaller gap, which is conservative).
//
// Near and far pairs. Most candidates are far beyond the range (the neighbor skin is chosen for
// the largest move between list builds), and looking at each of them at every evaluation costs
// more than the pairs that act. So a pass over all pairs also splits them: the near ones are
// closer than the threshold T = max(range, the smallest distance, capped at nearest) plus a
// margin; the far ones are not. Until an atom has moved margin / 2 from that pass, no far pair
// can come within T (a pair closes by at most twice the largest move), so an evaluation looks
// at the near pairs only: a far pair keeps the bound of the pass, less twice the largest move
// since (operator[]). A pass over all pairs comes again when an atom moved farther, when the
// candidates change, or when the near pairs' smallest distance rose above the far pairs' bound
// (the smallest distance must be one of the near ones). LAMMPS-free.

#ifndef PERISISSM_CONTACT_CANDIDATE_DISTANCES_H
#define PERISISSM_CONTACT_CANDIDATE_DISTANCES_H

#include "contact/candidates.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace PeriSISSM {

class CandidateDistances {
 public:
  // The distances of the candidates at positions x (nall atoms: owned and ghost), exact or
  // bounded as above. generation: a number that changes whenever the candidates (or the local
  // indices) do; range: dmin + dhat; nearest: a distance no pair needs exactly beyond (the
  // smallest distance found starts there); margin (> 0): how far beyond T the near pairs
  // reach. Marks the distances valid.
  void evaluate(const std::vector<Candidate> &candidates, const double *const *x, int nall,
                std::int64_t generation, double range, double nearest, double margin);
  // the positions moved from those of the last evaluation (the distances stay as bounds for
  // the next one)
  void invalidate() { valid_ = false; }
  bool valid() const { return valid_; }

  // pair ic's distance or a lower bound of it
  double operator[](std::size_t ic) const
  {
    return far_[ic] ? distance[ic] - stale_ : distance[ic];
  }
  bool exact(std::size_t ic) const { return exact_[ic] != 0; }
  // an exact pair's squared distance, as CollisionStencil::distance2() gave it (its distance
  // is the square root)
  double squared(std::size_t ic) const { return distance2[ic]; }
  // the distance of pair ic, from its square D, replaces its lower bound (a near pair's; a far
  // pair keeps its bound)
  void set_exact(std::size_t ic, double D)
  {
    if (far_[ic]) return;
    distance2[ic] = D;
    distance[ic] = std::sqrt(D);
    exact_[ic] = 1;
  }
  // the near pairs, in ascending order: every pair within the range, and the nearest one
  const std::vector<int> &near() const { return near_; }
  bool far(std::size_t ic) const { return far_[ic] != 0; }
  // no far pair is closer than this (+inf without far pairs)
  double far_bound() const { return far_floor_ - stale_; }
  // the number of candidates with Candidate::counts set
  long counted() const { return counted_; }
  // the smallest of distance - dmin (+inf for no pair)
  double smallest_gap(double dmin) const;
  // a lower bound of it, kept by evaluate() (the smallest distance then; set_exact() only
  // raises distances)
  double gap_bound(double dmin) const { return smallest_ - dmin; }
  // the bytes its arrays hold
  double memory_bytes() const;

 private:
  // the pairs idx (all: nullptr) at x, bounded by their points' moves moved[] where bounded
  // suffices (above); returns nearest, lowered to the exact distances found
  double pass(const std::vector<Candidate> &candidates, const double *const *x,
              const std::vector<int> *idx, bool bounded, const std::vector<double> &moved,
              double range, double nearest);
  // the near and far pairs at x (the distances current), from T = max(range, the smallest
  // distance capped at nearest)
  void split(const std::vector<Candidate> &candidates, const double *const *x, int nall,
             double range, double nearest, double margin);

  std::vector<double> distance;    // near: at the last evaluation; far: at the last split
  std::vector<double> distance2;   // the squares of the exact ones
  std::vector<char> exact_;
  std::vector<char> far_;
  std::vector<int> near_;
  struct NearPair {
    StencilType type;
    int v[4];
  };
  std::vector<NearPair> near_pairs_;    // the kinds and points of the near pairs
  double far_floor_ = HUGE_VAL;    // T + margin: every far pair's distance at the split
  double stale_ = 0.0;             // twice the largest move since the split
  double margin_ = 0.0;
  long counted_ = 0;
  bool valid_ = false;
  double smallest_ = 0.0;          // no larger than any distance
  std::vector<double> xlast;       // the positions of the last evaluation (3 per atom)
  std::vector<double> xsplit;      // those of the last split
  std::vector<double> moved;       // scratch: each atom's move
  std::int64_t xlast_generation = -1;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_CANDIDATE_DISTANCES_H
