// The arithmetic of the blow-up guard (fix nosb/family check_motion): the scan of atoms (a
// non-finite value by smallest ID, an atom beyond one periodic image of an orthogonal and a
// tilted box, the extent of the finite positions), the neighbor bins of fixed, shrink-wrapped
// and periodic dimensions, which kind stops the run, the distance outside the box, the record
// of the worst atom and the words for its non-finite values.
#include "peri/blowup_guard.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace PeriSISSM;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

}    // namespace

TEST(BlowupGuard, NonFiniteAtomsAreReportedBySmallestIdAndLeaveTheExtent)
{
  const double lo[3] = {0.0, 0.0, 0.0}, hinv[6] = {0.1, 0.1, 0.1, 0.0, 0.0, 0.0};
  const int pbc[3] = {0, 0, 0};
  const PeriodicCell cell = {lo, hinv, pbc};
  double scan[kGuardScan];
  clear_guard_scan(scan);
  for (int k = 0; k < kGuardScan; k++) EXPECT_EQ(scan[k], kGuardNone);

  const double zero[3] = {0.0, 0.0, 0.0}, x[3] = {1.0, -2.0, 3.0}, bad[3] = {0.0, kNan, 0.0};
  scan_atom_motion(x, zero, zero, 5.0, cell, scan);
  scan_atom_motion(bad, zero, zero, 9.0, cell, scan);
  const double far[3] = {1e300, 0.0, 0.0}, inf[3] = {0.0, 0.0, -kInf};
  scan_atom_motion(zero, zero, inf, 7.0, cell, scan);    // a force
  scan_atom_motion(far, zero, zero, 2.0, cell, scan);    // finite
  EXPECT_EQ(scan[0], -7.0);
  EXPECT_EQ(scan[1], kGuardNone);    // no periodic dimension
  EXPECT_EQ(scan[2], -1.0);          // -(smallest x)
  EXPECT_EQ(scan[3], 2.0);
  EXPECT_EQ(scan[4], -0.0);
  EXPECT_EQ(scan[5], 1e300);
  EXPECT_EQ(scan[6], 0.0);
  EXPECT_EQ(scan[7], 3.0);
  EXPECT_EQ(blowup_kind(scan, 1.0), 1);
}

TEST(BlowupGuard, AtomsBeyondOnePeriodicImage)
{
  // box [1, 11] x [0, 10] x [0, 10], periodic in x and y
  const double lo[3] = {1.0, 0.0, 0.0}, hinv[6] = {0.1, 0.1, 0.1, 0.0, 0.0, 0.0};
  const int pbc[3] = {1, 1, 0};
  const PeriodicCell cell = {lo, hinv, pbc};
  const double zero[3] = {0.0, 0.0, 0.0};
  double scan[kGuardScan];
  clear_guard_scan(scan);
  const double beyond[3] = {-8.9, 29.9, 1e6};    // fractional x -0.99, y 2.99 (beyond)
  const double edge[3] = {-9.0, 19.99, -1e6};    // fractional x -1.0, y 1.999; z not periodic
  scan_atom_motion(edge, zero, zero, 4.0, cell, scan);
  EXPECT_EQ(scan[1], kGuardNone);
  scan_atom_motion(beyond, zero, zero, 6.0, cell, scan);
  EXPECT_EQ(scan[1], -6.0);
  const double xbeyond[3] = {21.0, 0.0, 0.0};    // x fractional 2.0
  scan_atom_motion(xbeyond, zero, zero, 3.0, cell, scan);
  EXPECT_EQ(scan[1], -3.0);
  EXPECT_EQ(blowup_kind(scan, 1.0), 2);

  // tilted box: xy = 10 shifts x by a box length per box height in y
  const double hinv_tilt[6] = {0.1, 0.1, 0.1, 0.0, 0.0, -0.1};
  const PeriodicCell tilted = {lo, hinv_tilt, pbc};
  clear_guard_scan(scan);
  const double sheared[3] = {-14.0, 9.0, 0.0};    // fractional x -1.5 - 0.9 = -2.4
  scan_atom_motion(sheared, zero, zero, 8.0, tilted, scan);
  EXPECT_EQ(scan[1], -8.0);
  const double along[3] = {12.0, 9.0, 0.0};    // (11 - 9) / 10 = 0.2: inside
  clear_guard_scan(scan);
  scan_atom_motion(along, zero, zero, 8.0, tilted, scan);
  EXPECT_EQ(scan[1], kGuardNone);
}

TEST(BlowupGuard, NeighborBinsOfFixedShrinkWrappedAndPeriodicDimensions)
{
  const double boxlo[3] = {0.0, 0.0, 0.0}, boxhi[3] = {10.0, 10.0, 10.0};
  const double cutghost[3] = {1.0, 1.0, 1.0};
  // x periodic, y shrink-wrapped (2 2), z shrink-wrapped with a minimum (3 3)
  const int boundary[3][2] = {{0, 0}, {2, 2}, {3, 3}};
  const int periodic[3] = {1, 0, 0};
  double scan[kGuardScan];
  clear_guard_scan(scan);
  scan[2] = 5.0;     // smallest x -5 (periodic: ignored)
  scan[3] = -2.0;    // smallest y 2
  scan[4] = 3.0;     // smallest z -3
  scan[5] = 50.0;
  scan[6] = 4.0;    // largest y 4
  scan[7] = 6.0;    // largest z 6: the minimum box keeps 10
  double span[3];
  const double bins = neighbor_bins(boxlo, boxhi, boundary, periodic, cutghost, 2.0, scan, span);
  EXPECT_EQ(span[0], 10.0);
  EXPECT_EQ(span[1], 2.0);
  EXPECT_EQ(span[2], 13.0);
  EXPECT_DOUBLE_EQ(bins, (12.0 / 2.0 + 4.0) * (4.0 / 2.0 + 4.0) * (15.0 / 2.0 + 4.0));
  EXPECT_EQ(blowup_kind(scan, bins), 0);

  // no finite atom: the box as it is; binsize 0: one bin
  clear_guard_scan(scan);
  EXPECT_EQ(neighbor_bins(boxlo, boxhi, boundary, periodic, cutghost, 0.0, scan, span), 1.0);
  EXPECT_EQ(span[1], 10.0);

  // a shrink-wrapped dimension that exploded
  scan[3] = -0.0;
  scan[6] = 1e12;
  const double many = neighbor_bins(boxlo, boxhi, boundary, periodic, cutghost, 0.5, scan, span);
  EXPECT_GT(many, kMaxNeighborBins);
  EXPECT_EQ(blowup_kind(scan, many), 3);
  EXPECT_EQ(blowup_kind(scan, kMaxNeighborBins), 0);
}

TEST(BlowupGuard, DistanceOutsideTheBox)
{
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {1.0, 2.0, 3.0};
  const double in[3] = {0.5, 1.0, 1.5}, below[3] = {0.5, -4.0, 3.5}, above[3] = {7.0, 1.0, 0.0};
  EXPECT_EQ(distance_outside(in, lo, hi), 0.0);
  EXPECT_EQ(distance_outside(below, lo, hi), 4.0);
  EXPECT_EQ(distance_outside(above, lo, hi), 6.0);
}

TEST(BlowupGuard, WorstAtomRecordAndTheWordsForItsNonFiniteValues)
{
  const double x[3] = {1.0, 2.0, 3.0}, v[3] = {4.0, kInf, 6.0}, f[3] = {kNan, 0.0, 0.0};
  double rec[7];
  worst_atom_record(x, v, f, rec);
  EXPECT_EQ(rec[6], 6.0);
  EXPECT_EQ(rec[0], 1.0);
  EXPECT_EQ(rec[2], 3.0);
  for (int d = 0; d < 3; d++) EXPECT_EQ(rec[3 + d], 0.0);
  worst_atom_record(f, x, x, rec);
  EXPECT_EQ(rec[6], 1.0);
  EXPECT_EQ(rec[0], 0.0);
  EXPECT_EQ(rec[4], 2.0);

  EXPECT_EQ(nonfinite_names(1), "position");
  EXPECT_EQ(nonfinite_names(6), "velocity and force");
  EXPECT_EQ(nonfinite_names(5), "position and force");
  EXPECT_EQ(nonfinite_names(7), "position, velocity and force");
  EXPECT_EQ(nonfinite_names(0), "");
}
