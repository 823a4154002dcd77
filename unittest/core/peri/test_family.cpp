// Order of a bond family (by partner ID, whatever order the neighbor list gave) with the
// duplicate a too short periodic box makes, the damage of a particle from its broken bonds, the
// widths of a reference box, and the bonds that leave a group.
#include "peri/family.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

using namespace PeriSISSM;

TEST(FamilyOrder, PartnersAreSortedByIdWhateverTheListOrder)
{
  std::vector<std::pair<int64_t, int>> a = {{7, 3}, {2, 9}, {(int64_t(1) << 40), 0}, {5, 1}};
  std::vector<std::pair<int64_t, int>> b = {a[2], a[0], a[3], a[1]};
  EXPECT_EQ(order_family(a), 0);
  EXPECT_EQ(order_family(b), 0);
  EXPECT_EQ(a, b);
  const std::vector<std::pair<int64_t, int>> expected = {
      {2, 9}, {5, 1}, {7, 3}, {(int64_t(1) << 40), 0}};
  EXPECT_EQ(a, expected);

  std::vector<std::pair<int, int>> none;
  EXPECT_EQ(order_family(none), 0);
}

TEST(FamilyOrder, TwoImagesOfOneParticleAreReportedBySmallestId)
{
  // particles 8 and 4 both appear twice (two periodic images: different local indices)
  std::vector<std::pair<int, int>> f = {{8, 12}, {4, 2}, {8, 3}, {6, 5}, {4, 20}};
  EXPECT_EQ(order_family(f), 4);
  EXPECT_EQ(f[0], std::make_pair(4, 2));    // images by local index
  EXPECT_EQ(f[1], std::make_pair(4, 20));
}

TEST(FamilyDamage, BrokenBondsCountByTheirWeight)
{
  const int partner[4] = {3, 0, 9, 0};
  const double omega[4] = {1.0, 2.0, 0.5, 0.5};
  EXPECT_EQ(damage(4, partner, omega, 4.0), 1.0 - 1.5 / 4.0);
  const int intact[4] = {3, 4, 9, 10};
  EXPECT_EQ(damage(4, intact, omega, 4.0), 0.0);
  const int broken[4] = {0, 0, 0, 0};
  EXPECT_EQ(damage(4, broken, omega, 4.0), 1.0);
  // no initial family (a particle created later): no damage
  EXPECT_EQ(damage(0, partner, omega, 0.0), 0.0);
}

// the distances between opposite faces of a restricted triclinic box (edge vectors a = (xprd,
// 0, 0), b = (xy, yprd, 0), c = (xz, yz, zprd)): the volume over the area of each face pair
TEST(ReferenceBoxWidths, VolumeOverFaceArea)
{
  ReferenceBox box;
  box.box[0] = 2.0;
  box.box[1] = 3.0;
  box.box[2] = 5.0;
  double w[3];
  box.face_distances(w);
  EXPECT_EQ(w[0], 2.0);
  EXPECT_EQ(w[1], 3.0);
  EXPECT_EQ(w[2], 5.0);
  box.box[3] = 0.7;     // yz
  box.box[4] = -1.1;    // xz
  box.box[5] = 0.4;     // xy
  box.face_distances(w);
  const double a[3] = {2.0, 0.0, 0.0}, b[3] = {0.4, 3.0, 0.0}, c[3] = {-1.1, 0.7, 5.0};
  const auto cross_norm = [](const double *u, const double *v) {
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
                 z = u[0] * v[1] - u[1] * v[0];
    return std::sqrt(x * x + y * y + z * z);
  };
  const double volume = 2.0 * 3.0 * 5.0;
  EXPECT_NEAR(w[0], volume / cross_norm(b, c), 1e-14);
  EXPECT_NEAR(w[1], volume / cross_norm(c, a), 1e-14);
  EXPECT_NEAR(w[2], volume / cross_norm(a, b), 1e-14);
  EXPECT_LT(w[0], 2.0);
  EXPECT_LT(w[1], 3.0);
}

// owned particles 0 .. 2, ghost 3; particles 0, 1 and the ghost in the group (bit 2)
TEST(FamilyGroup, UnbrokenBondsLeavingTheGroupAreFound)
{
  int npartner[3] = {2, 1, 1};
  int j0[2] = {1, 3}, j1[1] = {2}, j2[1] = {0};
  int *jlocal[3] = {j0, j1, j2};
  Families fam;
  fam.npartner = npartner;
  fam.jlocal = jlocal;
  const int mask[4] = {1 | 2, 1 | 2, 1, 1 | 2};
  EXPECT_TRUE(bonds_leave_group(fam, 3, mask, 2));    // 1 - 2
  j1[0] = -1;                                         // broken
  EXPECT_FALSE(bonds_leave_group(fam, 3, mask, 2));
  EXPECT_FALSE(bonds_leave_group(fam, 3, mask, 1));    // every particle in group bit 1
  EXPECT_FALSE(bonds_leave_group(fam, 3, mask, 4));    // no particle in group bit 4
  const int ghost_out[4] = {1 | 2, 1 | 2, 1, 1};
  EXPECT_TRUE(bonds_leave_group(fam, 3, ghost_out, 2));    // 0 - ghost 3
}
