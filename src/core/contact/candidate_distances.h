// The distances of a set of candidate pairs (candidates.h) at the last force evaluation, kept
// for the next evaluation and for the path limit (path_limit.h).
//
// Since the last evaluation of the same candidates a pair's distance shrank at most by how far a
// point of each primitive moved (CollisionStencil::closing()): when that lower bound is beyond
// the barrier's range and not below the smallest distance found so far, the pair neither acts
// nor is the nearest, and the bound stands in for the distance (exact(ic) is then false; the
// path limit takes it as a smaller gap, which is conservative). LAMMPS-free.

#ifndef PERISISSM_CONTACT_CANDIDATE_DISTANCES_H
#define PERISISSM_CONTACT_CANDIDATE_DISTANCES_H

#include "contact/candidates.h"

#include <cstdint>
#include <vector>

namespace PeriSISSM {

class CandidateDistances {
 public:
  // The distances of the candidates at positions x (nall atoms: owned and ghost), exact or
  // bounded as above. generation: a number that changes whenever the candidates (or the local
  // indices) do; range: dmin + dhat; nearest: a distance no pair needs exactly beyond (the
  // smallest distance found starts there). Marks the distances valid.
  void evaluate(const std::vector<Candidate> &candidates, const double *const *x, int nall,
                std::int64_t generation, double range, double nearest);
  // the positions moved from those of the last evaluation (the distances stay as bounds for
  // the next one)
  void invalidate() { valid_ = false; }
  bool valid() const { return valid_; }

  double operator[](std::size_t ic) const { return distance[ic]; }
  bool exact(std::size_t ic) const { return exact_[ic] != 0; }
  // the distance of pair ic replaces its lower bound
  void set_exact(std::size_t ic, double d)
  {
    distance[ic] = d;
    exact_[ic] = 1;
  }
  // the smallest of distance - dmin (+inf for no pair)
  double smallest_gap(double dmin) const;
  // a lower bound of it, kept by evaluate() (the smallest distance then; set_exact() only
  // raises distances)
  double gap_bound(double dmin) const { return smallest_ - dmin; }

 private:
  std::vector<double> distance;
  std::vector<char> exact_;
  bool valid_ = false;
  double smallest_ = 0.0;    // no larger than any distance
  std::vector<double> xlast;    // the positions of the last evaluation (3 per atom)
  std::int64_t xlast_generation = -1;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_CANDIDATE_DISTANCES_H
