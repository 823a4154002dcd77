#include "peri/contact_candidates.h"

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
