// The arithmetic of the blow-up guard (peri/blowup_guard.h).

#include "peri/blowup_guard.h"

#include "linalg/general_format.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace PeriSISSM {

namespace {

  // "(x, y, z)" with 4 significant digits
  std::string point(const double x[3])
  {
    return "(" + general_format(x[0], 4) + ", " + general_format(x[1], 4) + ", " +
        general_format(x[2], 4) + ")";
  }

}    // namespace

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

std::string likely_cause(int converged, double dt, double est)
{
  if (converged == 0)
    return "fix sissm stopped at its iteration limit without converging, at time step dt = " +
        general_format(dt, 4) + " (" + general_format(dt / est, 3) +
        " x the estimated explicit stable time step " + general_format(est, 4) +
        " of peri/nosb): lower the time step or raise its iterations" +
        (dt <= est ? "; with a time step this small, check the initial velocities and external "
                     "forces as well"
                   : "");
  if (converged == 1)
    return "fix sissm converged in this step (dt = " + general_format(dt, 4) +
        "), so the motion was put in from outside: check initial velocities and positions "
        "(velocity, set, displace_atoms) and fixes that add forces";
  if (dt > est)
    return "time step dt = " + general_format(dt, 4) + " is above the estimated stable time step " +
        general_format(est, 4) +
        " of peri/nosb (compute nosb/atom column 11, formula in the pair_style peri/nosb doc)";
  return "time step dt = " + general_format(dt, 4) + " is within the estimated stable time step " +
      general_format(est, 4) +
      " of peri/nosb at rest (compute nosb/atom column 11): either the body is deformed far "
      "from rest (strongly compressed or inverted particles are stiffer: lower the time step), "
      "or the motion was put in from outside (check initial velocities and positions: velocity, "
      "set, displace_atoms; and fixes that add forces)";
}

std::string blowup_message(int kind, long long step, long long worst, const double rec[7],
                           const double span[3], double dt, const std::string &cause)
{
  const double speed = std::sqrt(rec[3] * rec[3] + rec[4] * rec[4] + rec[5] * rec[5]);
  const std::string at = "Pair peri/nosb: the run is unstable: at step " + std::to_string(step);
  const std::string id = std::to_string(worst);
  const std::string v = general_format(speed, 4), vdt = general_format(speed * dt, 4);
  if (kind == 1)
    return at + " atom " + id + " has a non-finite " + nonfinite_names((int) rec[6]) +
        "; likely cause: " + cause;
  if (kind == 2)
    return at + " atom " + id + " is at " + point(rec) +
        ", more than one box length outside the periodic box (speed " + v + ", " + vdt +
        " per step); likely cause: " + cause;
  return at + " the atoms span " + general_format(span[0], 4) + " x " + general_format(span[1], 4) +
      " x " + general_format(span[2], 4) + ", too far for LAMMPS's neighbor bins; atom " + id +
      " is farthest from the box of the last neighbor list build, at " + point(rec) + ", speed " +
      v + " (" + vdt + " per step); likely cause: " + cause;
}

}    // namespace PeriSISSM
