// The arithmetic of the blow-up guard (peri/blowup_guard.h).

#include "peri/blowup_guard.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace PeriSISSM {

void clear_guard_scan(double scan[kGuardScan])
{
  for (int k = 0; k < kGuardScan; k++) scan[k] = kGuardNone;
}

void scan_atom_motion(const double x[3], const double v[3], const double f[3], double id,
                      const PeriodicCell &cell, double scan[kGuardScan])
{
  const double sum = x[0] + x[1] + x[2] + v[0] + v[1] + v[2] + f[0] + f[1] + f[2];
  if (!std::isfinite(sum)) {
    scan[0] = std::max(scan[0], -id);
    return;
  }
  const int *pbc = cell.periodic;
  if (pbc[0] || pbc[1] || pbc[2]) {
    // fractional coordinates: Domain::pbc() can bring back atoms within [-1, 2)
    const double *h = cell.hinv;
    const double d0 = x[0] - cell.lo[0], d1 = x[1] - cell.lo[1], d2 = x[2] - cell.lo[2];
    const double l[3] = {h[0] * d0 + h[5] * d1 + h[4] * d2, h[1] * d1 + h[3] * d2, h[2] * d2};
    for (int d = 0; d < 3; d++)
      if (pbc[d] && (l[d] < -1.0 || l[d] >= 2.0)) scan[1] = std::max(scan[1], -id);
  }
  for (int d = 0; d < 3; d++) {
    scan[2 + d] = std::max(scan[2 + d], -x[d]);
    scan[5 + d] = std::max(scan[5 + d], x[d]);
  }
}

double neighbor_bins(const double boxlo[3], const double boxhi[3], const int boundary[3][2],
                     const int periodic[3], const double cutghost[3], double binsize,
                     const double scan[kGuardScan], double span[3])
{
  double bins = 1.0;
  for (int d = 0; d < 3; d++) {
    double blo = boxlo[d], bhi = boxhi[d];
    if (!periodic[d] && scan[5 + d] > kGuardNone) {
      if (boundary[d][0] == 2) blo = -scan[2 + d];
      if (boundary[d][0] == 3) blo = std::min(blo, -scan[2 + d]);
      if (boundary[d][1] == 2) bhi = scan[5 + d];
      if (boundary[d][1] == 3) bhi = std::max(bhi, scan[5 + d]);
    }
    span[d] = bhi - blo;
    if (binsize > 0.0) bins *= (span[d] + 2.0 * cutghost[d]) / binsize + 4.0;
  }
  return bins;
}

int blowup_kind(const double scan[kGuardScan], double bins)
{
  if (scan[0] > kGuardNone) return 1;
  if (scan[1] > kGuardNone) return 2;
  return bins > kMaxNeighborBins ? 3 : 0;
}

double distance_outside(const double x[3], const double lo[3], const double hi[3])
{
  double out = 0.0;
  for (int d = 0; d < 3; d++) out = std::max(out, std::max(lo[d] - x[d], x[d] - hi[d]));
  return out;
}

void worst_atom_record(const double x[3], const double v[3], const double f[3], double rec[7])
{
  int bad = 0;
  for (int d = 0; d < 3; d++) {
    if (!std::isfinite(x[d])) bad |= 1;
    if (!std::isfinite(v[d])) bad |= 2;
    if (!std::isfinite(f[d])) bad |= 4;
  }
  rec[6] = bad;
  for (int d = 0; d < 3; d++) {
    rec[d] = (bad & 1) ? 0.0 : x[d];
    rec[3 + d] = (bad & 2) ? 0.0 : v[d];
  }
}

std::string nonfinite_names(int flags)
{
  std::vector<std::string> names;
  if (flags & 1) names.emplace_back("position");
  if (flags & 2) names.emplace_back("velocity");
  if (flags & 4) names.emplace_back("force");
  std::string what;
  for (size_t k = 0; k < names.size(); k++)
    what += (k == 0 ? "" : (k + 1 == names.size() ? " and " : ", ")) + names[k];
  return what;
}

}    // namespace PeriSISSM
