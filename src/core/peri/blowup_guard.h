// The arithmetic of the blow-up guard of fix nosb/family (check_motion): a scan of the owned
// atoms for non-finite values, atoms beyond one periodic image (Domain::pbc shifts by one box
// length only) and the extent of the finite positions; the neighbor bins LAMMPS would need for
// that extent; which of the three stops the run; the worst atom and what is reported about it;
// and the error message. The glue gives the reduction over processes and stops the run. LAMMPS's own test of the bin count multiplies the counts in 64-bit
// integers, which wrap around for a box that exploded within one step, and then writes outside
// its bin array (signal 11 in NBinStandard::bin_atoms): hence the guard's own count.

#ifndef PERISISSM_PERI_BLOWUP_GUARD_H
#define PERISISSM_PERI_BLOWUP_GUARD_H

#include <algorithm>
#include <cfloat>
#include <string>

namespace PeriSISSM {

// value of an empty slot of a scan or of an atom's record (below every value a slot takes)
constexpr double kGuardNone = -DBL_MAX;
// doubles of a scan, each a maximum over atoms: -(smallest ID with a non-finite position,
// velocity or force), -(smallest ID beyond one periodic image), -(smallest x, y, z),
// largest x, y, z of the finite positions
constexpr int kGuardScan = 8;
// 2^30: half of the neighbor bins LAMMPS can index
constexpr double kMaxNeighborBins = 1073741824.0;

// a scan of no atom (every slot kGuardNone)
void clear_guard_scan(double scan[kGuardScan]);

// The periodic cell of the box: lower corner lo, the inverse h_inv of LAMMPS's shape matrix
// (xx yy zz yz xz xy) and which dimensions are periodic.
struct PeriodicCell {
  const double *lo;
  const double *hinv;
  const int *periodic;
};

// Folds one atom (position x, velocity v, force f, ID id) into scan. An atom with a finite sum
// of its nine values counts for the extent; beyond one image means a fractional coordinate of a
// periodic dimension outside [-1, 2).
void scan_atom_motion(const double x[3], const double v[3], const double f[3], double id,
                      const PeriodicCell &cell, double scan[kGuardScan]);

// Neighbor bins of LAMMPS if it rebuilt its lists now, for the scan reduced over all atoms:
// the box of a non-periodic dimension is reset to the atoms (boundary code 2, shrink-wrapped),
// to at least the box it has (code 3, shrink-wrapped with a minimum) or stays fixed (code 1);
// bins of size binsize over the box plus the ghost cutoff at both ends, and 4 more per
// dimension. Outputs: span (the box extent per dimension). Returns the product of the bin
// counts (1 when binsize <= 0).
double neighbor_bins(const double boxlo[3], const double boxhi[3], const int boundary[3][2],
                     const int periodic[3], const double cutghost[3], double binsize,
                     const double scan[kGuardScan], double span[3]);

// The box as the guard sees it: the periodic cell, the upper corner, LAMMPS's boundary codes
// and ghost cutoff per dimension, and the size of the neighbor bins.
struct GuardBox {
  PeriodicCell cell;
  const double *hi;
  const int (*boundary)[2];
  const double *cutghost;
  double binsize;
};

// What stops the run: 1 a non-finite value, 2 an atom beyond one periodic image, 3 more bins
// than kMaxNeighborBins, 0 nothing (scan reduced over all atoms).
int blowup_kind(const double scan[kGuardScan], double bins);

// How far position x lies outside the box [lo, hi] (largest over dimensions, 0 inside).
double distance_outside(const double x[3], const double lo[3], const double hi[3]);

// Record of the worst atom: position (0 if not finite), velocity (0 if not finite), and the
// flags of the non-finite values (1 position, 2 velocity, 4 force) as the last double.
void worst_atom_record(const double x[3], const double v[3], const double f[3], double rec[7]);

// The row among 0..n-1 (positions x, 3 per row, IDs tag) farthest outside the box [lo, hi]
// (distance_outside), the smallest ID among equals: its distance in far and its ID in id
// (-1 and 0 when n is 0). Id is the integer type of atom IDs.
template <class Id>
void farthest_outside(int n, const double *x, const Id *tag, const double lo[3], const double hi[3],
                      double &far, Id &id)
{
  far = -1.0;
  id = 0;
  for (int i = 0; i < n; i++) {
    const double out = distance_outside(x + 3 * i, lo, hi);
    if (out > far || (out == far && tag[i] < id)) {
      far = out;
      id = tag[i];
    }
  }
}

// The blow-up guard over the owned atoms 0..n-1 of every process (x, v, f three per row, IDs
// tag; Id the integer type of atom IDs); reduce_max(buf, m) reduces m doubles over all
// processes by maximum, in place (every process calls it equally often). Returns the kind
// (blowup_kind; 0: nothing stops the run and nothing else is set). For a kind: the worst atom
// (the smallest ID of that kind for kinds 1 and 2, else the atom farthest outside the box,
// smallest ID among equals; the same on any number of processes), its record from its owner
// (worst_atom_record) and the span of neighbor_bins. IDs pass through doubles (exact to 2^53).
template <class Id, class ReduceMax>
int guard_motion(int n, const double *x, const double *v, const double *f, const Id *tag,
                 const GuardBox &box, ReduceMax reduce_max, Id &worst, double rec[7],
                 double span[3])
{
  double scan[kGuardScan];
  clear_guard_scan(scan);
  for (int i = 0; i < n; i++)
    scan_atom_motion(x + 3 * i, v + 3 * i, f + 3 * i, (double) tag[i], box.cell, scan);
  reduce_max(scan, kGuardScan);
  const double bins = neighbor_bins(box.cell.lo, box.hi, box.boundary, box.cell.periodic,
                                    box.cutghost, box.binsize, scan, span);
  const int kind = blowup_kind(scan, bins);
  if (!kind) return 0;
  if (kind < 3) {
    worst = (Id) (-scan[kind - 1]);
  } else {
    double far, farall;
    Id id;
    farthest_outside(n, x, tag, box.cell.lo, box.hi, far, id);
    farall = far;
    reduce_max(&farall, 1);
    double mine = (far == farall) ? -(double) id : kGuardNone;
    reduce_max(&mine, 1);
    worst = (Id) (-mine);
  }
  std::fill(rec, rec + 7, kGuardNone);
  for (int i = 0; i < n; i++)
    if (tag[i] == worst) worst_atom_record(x + 3 * i, v + 3 * i, f + 3 * i, rec);
  reduce_max(rec, 7);
  return kind;
}

// The likely cause of a blow-up, from the integrator (converged: 1 its step converged, 0 it
// stopped at its iteration limit, -1 explicit integrators), the time step dt and the estimated
// stable time step est (stable_time_step, smallest over all particles).
std::string likely_cause(int converged, double dt, double est);

// The error message of a blow-up of a kind (blowup_kind) at step: the worst atom's ID and record
// rec (worst_atom_record), the span of neighbor_bins (kind 3), the time step dt and the likely
// cause.
std::string blowup_message(int kind, long long step, long long worst, const double rec[7],
                           const double span[3], double dt, const std::string &cause);

// The non-finite values of flags as words: "position", "velocity and force", "position,
// velocity and force"...
std::string nonfinite_names(int flags);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_BLOWUP_GUARD_H
