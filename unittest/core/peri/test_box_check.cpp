// Tests of the periodic box check (peri/box_check.h): a periodic direction narrower than two
// horizons is named with its width (orthogonal and tilted boxes), non-periodic ones are not.

#include "peri/box_check.h"

#include <gtest/gtest.h>

#include <string>

using PeriSISSM::periodic_box_problem;
using PeriSISSM::ReferenceBox;

TEST(PeriodicBoxCheck, NarrowPeriodicDirectionsAreNamed)
{
  ReferenceBox box;
  box.box[0] = 2.0;
  box.box[1] = 0.9;
  box.box[2] = 5.0;
  const int all[3] = {1, 1, 1}, xz[3] = {1, 0, 1};
  EXPECT_EQ(periodic_box_problem(box, all, 0.45), "");    // exactly two horizons: allowed
  EXPECT_EQ(periodic_box_problem(box, all, 0.5),
            "Pair style peri/nosb: the periodic box is 0.9 wide in y, shorter than two horizons "
            "(2 x 0.5): enlarge the box or make that direction non-periodic");
  EXPECT_EQ(periodic_box_problem(box, xz, 0.5), "");
  const std::string x = periodic_box_problem(box, xz, 1.25);
  EXPECT_NE(x.find("is 2 wide in x,"), std::string::npos) << x;
  // a tilt narrows the y faces' distance to 30 / |(0, 10, -8)| = 2.3426...
  box.box[1] = 3.0;
  box.box[3] = 4.0;    // yz
  double w[3];
  box.face_distances(w);
  ASSERT_LT(w[1], 2.35);
  const int y_only[3] = {0, 1, 0};
  EXPECT_EQ(periodic_box_problem(box, y_only, 1.17), "");
  const std::string y = periodic_box_problem(box, y_only, 1.18);
  EXPECT_NE(y.find("is 2.3426064 wide in y,"), std::string::npos) << y;
}
