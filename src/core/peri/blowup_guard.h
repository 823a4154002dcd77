// The arithmetic of the blow-up guard of fix nosb/family (check_motion): a scan of the owned
// atoms for non-finite values, atoms beyond one periodic image (Domain::pbc shifts by one box
// length only) and the extent of the finite positions; the neighbor bins LAMMPS would need for
// that extent; which of the three stops the run; and what is reported about the worst atom.
// The glue reduces the scans of all processes by maximum, picks the worst atom and prints.

#ifndef PERISISSM_PERI_BLOWUP_GUARD_H
#define PERISISSM_PERI_BLOWUP_GUARD_H

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

// What stops the run: 1 a non-finite value, 2 an atom beyond one periodic image, 3 more bins
// than kMaxNeighborBins, 0 nothing (scan reduced over all atoms).
int blowup_kind(const double scan[kGuardScan], double bins);

// How far position x lies outside the box [lo, hi] (largest over dimensions, 0 inside).
double distance_outside(const double x[3], const double lo[3], const double hi[3]);

// Record of the worst atom: position (0 if not finite), velocity (0 if not finite), and the
// flags of the non-finite values (1 position, 2 velocity, 4 force) as the last double.
void worst_atom_record(const double x[3], const double v[3], const double f[3], double rec[7]);

// The non-finite values of flags as words: "position", "velocity and force", "position,
// velocity and force"...
std::string nonfinite_names(int flags);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_BLOWUP_GUARD_H
