// The arithmetic of the blow-up guard (fix nosb/family check_motion): the scan of atoms (a
// non-finite value by smallest ID, an atom beyond one periodic image of an orthogonal and a
// tilted box, the extent of the finite positions), the neighbor bins of fixed, shrink-wrapped
// and periodic dimensions, which kind stops the run, the distance outside the box, the record
// of the worst atom and the words for its non-finite values; the guard over the atoms of two
// processes (the worst atom and its record from its owner) and its messages.
#include "peri/blowup_guard.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

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

TEST(BlowupGuard, FarthestOutsideTakesTheSmallestIdAmongEquals)
{
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {1.0, 1.0, 1.0};
  // rows: inside; 2 beyond x; 2 below z (ID 9 and ID 4); 0.5 beyond y
  const double x[15] = {0.5,  0.5, 0.5, 3.0,  0.5, 0.5, 0.5, 0.5,
                        -2.0, 0.5, 0.5, -2.0, 0.5, 1.5, 0.5};
  const long long tag[5] = {1, 9, 8, 4, 2};
  double far = 0.0;
  long long id = 0;
  farthest_outside(5, x, tag, lo, hi, far, id);
  EXPECT_EQ(far, 2.0);
  EXPECT_EQ(id, 4);
  farthest_outside(2, x, tag, lo, hi, far, id);
  EXPECT_EQ(far, 2.0);
  EXPECT_EQ(id, 9);
  farthest_outside(1, x, tag, lo, hi, far, id);
  EXPECT_EQ(far, 0.0);
  EXPECT_EQ(id, 1);
  farthest_outside(0, x, tag, lo, hi, far, id);
  EXPECT_EQ(far, -1.0);
  EXPECT_EQ(id, 0);
}

TEST(BlowupGuard, LikelyCauseFromTheIntegratorAndTheTimeStep)
{
  // fix sissm at its iteration limit: the ratio, and the hint on velocities only when dt is
  // within the estimate
  EXPECT_EQ(likely_cause(0, 0.02, 0.0125),
            "fix sissm stopped at its iteration limit without converging, at time step dt = 0.02 "
            "(1.6 x the estimated explicit stable time step 0.0125 of peri/nosb): lower the time "
            "step or raise its iterations");
  const std::string small = likely_cause(0, 0.01, 0.0125);
  EXPECT_NE(small.find("(0.8 x the estimated"), std::string::npos);
  EXPECT_NE(small.find("; with a time step this small, check the initial velocities and "
                       "external forces as well"),
            std::string::npos);
  EXPECT_EQ(likely_cause(1, 1.234567e-5, 0.0125),
            "fix sissm converged in this step (dt = 1.235e-05), so the motion was put in from "
            "outside: check initial velocities and positions (velocity, set, displace_atoms) "
            "and fixes that add forces");
  EXPECT_EQ(likely_cause(-1, 0.09014, 0.0123456),
            "time step dt = 0.09014 is above the estimated stable time step 0.01235 of peri/nosb "
            "(compute nosb/atom column 11, formula in the pair_style peri/nosb doc)");
  const std::string within = likely_cause(-1, 0.01, 0.0125);
  EXPECT_EQ(within.find("time step dt = 0.01 is within the estimated stable time step 0.0125 of "
                        "peri/nosb at rest"),
            0u);
  EXPECT_NE(within.find("strongly compressed or inverted"), std::string::npos);
  // no stiffness anywhere: an infinite estimate
  EXPECT_NE(likely_cause(-1, 0.01, kInf).find("stable time step inf of"), std::string::npos);
}

TEST(BlowupGuard, MessagesOfTheThreeKinds)
{
  const double rec[7] = {1.5, -2.0, 123456.0, 3.0, 4.0, 0.0, 2.0}, span[3] = {2.166e5, 1.0, 0.5};
  EXPECT_EQ(blowup_message(1, 7, 42, rec, span, 0.1, "C"),
            "Pair peri/nosb: the run is unstable: at step 7 atom 42 has a non-finite velocity; "
            "likely cause: C");
  EXPECT_EQ(blowup_message(2, 8, 1099511627776LL, rec, span, 0.1, "C"),
            "Pair peri/nosb: the run is unstable: at step 8 atom 1099511627776 is at (1.5, -2, "
            "1.235e+05), more than one box length outside the periodic box (speed 5, 0.5 per "
            "step); likely cause: C");
  EXPECT_EQ(blowup_message(3, 2, 22, rec, span, 0.1, "C"),
            "Pair peri/nosb: the run is unstable: at step 2 the atoms span 2.166e+05 x 1 x 0.5, "
            "too far for LAMMPS's neighbor bins; atom 22 is farthest from the box of the last "
            "neighbor list build, at (1.5, -2, 1.235e+05), speed 5 (0.5 per step); likely "
            "cause: C");
}

namespace {

// A second process for guard_motion: its contribution to each reduction, in call order, is
// maxed into the buffer (calls counts the reductions).
struct OtherProcess {
  std::vector<std::vector<double>> parts;
  int calls = 0;
  void operator()(double *buf, int n)
  {
    ASSERT_LT(calls, (int) parts.size());
    ASSERT_EQ((int) parts[calls].size(), n);
    for (int k = 0; k < n; k++) buf[k] = std::max(buf[k], parts[calls][k]);
    calls++;
  }
};

}    // namespace

TEST(BlowupGuard, GuardMotionOverTwoProcesses)
{
  // box [0, 10]^3, z shrink-wrapped, x and y fixed; bins of size 1
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {10.0, 10.0, 10.0};
  const double hinv[6] = {0.1, 0.1, 0.1, 0.0, 0.0, 0.0}, cutghost[3] = {1.0, 1.0, 1.0};
  const int pbc[3] = {0, 0, 0}, boundary[3][2] = {{1, 1}, {1, 1}, {2, 2}};
  const GuardBox box = {{lo, hinv, pbc}, hi, boundary, cutghost, 1.0};
  const double v[6] = {0.0, 0.0, 3.0, 0.0, 4.0, 0.0}, f[6] = {0, 0, 0, 0, 0, 0};
  const long long tag[2] = {5, 6};
  long long worst = -1;
  double rec[7], span[3];

  // all inside, on both processes: nothing
  const double inside[6] = {1, 1, 1, 2, 2, 2};
  OtherProcess quiet;
  quiet.parts = {std::vector<double>(kGuardScan, kGuardNone)};
  quiet.parts[0][7] = 9.0;
  EXPECT_EQ(guard_motion(2, inside, v, f, tag, box, std::ref(quiet), worst, rec, span), 0);
  EXPECT_EQ(quiet.calls, 1);
  EXPECT_EQ(worst, -1);

  // the other process has atom 3 with a non-finite value: reported from its owner
  OtherProcess nan;
  nan.parts = {std::vector<double>(kGuardScan, kGuardNone), std::vector<double>(7, kGuardNone)};
  nan.parts[0][0] = -3.0;
  nan.parts[1] = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 4.0};
  EXPECT_EQ(guard_motion(2, inside, v, f, tag, box, std::ref(nan), worst, rec, span), 1);
  EXPECT_EQ(nan.calls, 2);
  EXPECT_EQ(worst, 3);
  EXPECT_EQ(rec[6], 4.0);
  EXPECT_EQ(rec[3], 1.0);

  // the z extent explodes here (atom 6 at z 1e12) and there (atom 2 below z 0, as far out):
  // the smallest ID among the farthest, its record from the other process
  const double exploded[6] = {1, 1, 1, 2, 2, 1e12};
  OtherProcess far;
  far.parts = {std::vector<double>(kGuardScan, kGuardNone),
               {1e12 - 10.0},
               {-2.0},
               {1.0, 1.0, 10.0 - 1e12, 7.0, 0.0, 0.0, 0.0}};
  far.parts[0][4] = 1e12 - 10.0;
  EXPECT_EQ(guard_motion(2, exploded, v, f, tag, box, std::ref(far), worst, rec, span), 3);
  EXPECT_EQ(far.calls, 4);
  EXPECT_EQ(worst, 2);
  EXPECT_EQ(rec[2], 10.0 - 1e12);
  EXPECT_EQ(rec[3], 7.0);
  EXPECT_EQ(span[2], 2e12 - 10.0);

  // alone, atom 6 is the farthest: its own record
  const auto alone = [](double *, int) {
  };
  EXPECT_EQ(guard_motion(2, exploded, v, f, tag, box, alone, worst, rec, span), 3);
  EXPECT_EQ(worst, 6);
  EXPECT_EQ(rec[2], 1e12);
  EXPECT_EQ(rec[4], 4.0);
  EXPECT_EQ(rec[6], 0.0);
}
