// The candidate pairs of short-range contact (contact.h's ContactCandidates) chosen from a
// neighbor list: for each listed atom i, its neighbors j with |x_i - x_j| < rc, in the list's
// order. The caller picks rc = the contact reach + a margin that covers the motion until the
// pairs are chosen again (contact/motion_tracker.h). LAMMPS-free.

#ifndef PERISISSM_PERI_CONTACT_CANDIDATES_H
#define PERISISSM_PERI_CONTACT_CANDIDATES_H

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

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_CONTACT_CANDIDATES_H
