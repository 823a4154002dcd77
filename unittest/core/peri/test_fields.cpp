// The messages of the halo (peri/fields.h): the rows of several fields of a list of particles,
// packed field after field per particle and unpacked into other rows unchanged; the reverse
// message of one field added to the owners.
#include "peri/fields.h"

#include <gtest/gtest.h>

#include <vector>

using namespace PeriSISSM;

TEST(HaloRows, PackedRowsUnpackIntoTheGhostRows)
{
  // 5 rows of a 3-wide and a 1-wide field; rows 0 .. 2 owned, 3 and 4 the ghosts of 2 and 0
  std::vector<double> a(15), b(5, -1.0);
  for (int i = 0; i < 15; i++) a[i] = i < 9 ? 10.0 * i + 1.0 : -1.0;
  for (int i = 0; i < 3; i++) b[i] = 0.5 * i;
  const HaloField fields[2] = {{a.data(), 3}, {b.data(), 1}};
  const int list[2] = {2, 0};
  double buf[8];
  EXPECT_EQ(pack_halo_rows(fields, 2, 2, list, buf), 8);
  const double expected[8] = {61.0, 71.0, 81.0, 1.0, 1.0, 11.0, 21.0, 0.0};
  for (int m = 0; m < 8; m++) EXPECT_EQ(buf[m], expected[m]) << m;
  unpack_halo_rows(fields, 2, 2, 3, buf);
  for (int k = 0; k < 3; k++) {
    EXPECT_EQ(a[9 + k], a[6 + k]);
    EXPECT_EQ(a[12 + k], a[k]);
  }
  EXPECT_EQ(b[3], b[2]);
  EXPECT_EQ(b[4], b[0]);
  EXPECT_EQ(b[1], 0.5);    // owned rows untouched
}

TEST(HaloRows, ReverseRowsAddTheGhostRowsToTheirOwners)
{
  // 5 rows of a 2-wide field; rows 3 and 4 the ghosts of 2 and 0
  std::vector<double> a = {1, 2, 3, 4, 5, 6, 0.5, 0.25, 10, 20};
  double buf[4];
  EXPECT_EQ(pack_reverse_rows(a.data(), 2, 2, 3, buf), 4);
  const double expected[4] = {0.5, 0.25, 10.0, 20.0};
  for (int m = 0; m < 4; m++) EXPECT_EQ(buf[m], expected[m]) << m;
  const int list[2] = {2, 0};
  add_reverse_rows(a.data(), 2, 2, list, buf);
  const std::vector<double> sums = {11, 22, 3, 4, 5.5, 6.25, 0.5, 0.25, 10, 20};
  EXPECT_EQ(a, sums);
}
