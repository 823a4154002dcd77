// Per-atom records of the bond families (fix nosb/family): the exchange and restart layout
// field by field (the layout of existing restart files), round trips for 32- and 64-bit IDs
// (IDs beyond 2^53 exactly) that drop broken bonds, copies of every slot, cleared rows and the
// record sizes.
#include "family_storage.h"
#include "peri/family_records.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

using namespace PeriSISSM;

namespace {

template <class Id> void round_trip(Id big)
{
  FamilyStorage<Id> s(3);
  s.fill(0, big, {Id(5), Id(0), big - 1, Id(0), Id(2)});
  const auto a = s.arrays();
  std::vector<double> buf(family_record_size(kMaxBonds), -1.0);
  const int m = pack_family(a, 0, buf.data());
  EXPECT_EQ(m, family_record_size(3));
  EXPECT_EQ(unbroken_bonds(a, 0), 3);

  EXPECT_EQ(unpack_family(a, 2, buf.data()), m);
  ASSERT_EQ(s.npartner[2], 3);    // the broken bonds are left out, the order kept
  const Id ids[3] = {Id(5), big - 1, Id(2)};
  const double omegas[3] = {0.1 * 1, 0.1 * 3, 0.1 * 5};    // of slots 0, 2, 4
  for (int b = 0; b < 3; b++) {
    EXPECT_EQ(s.partner[2][b], ids[b]);
    EXPECT_EQ(s.omega[2][b], omegas[b]);
  }
  for (int k = 0; k < 9; k++) EXPECT_EQ(s.kinv[2][k], s.kinv[0][k]);
  EXPECT_EQ(s.kregular[2], 1);
  EXPECT_EQ(s.vinit[2], 2.5);
  EXPECT_EQ(s.lamref[2], 3.25);
  EXPECT_EQ(s.owntag[2], big);
  EXPECT_EQ(s.jlocal[2][0], -7);    // jlocal is not part of the record
}

}    // namespace

TEST(FamilyRecords, SizesCountTheUnbrokenBonds)
{
  EXPECT_EQ(family_record_size(0), 1 + kFamilyAtomScalars);
  EXPECT_EQ(family_record_size(4), 1 + 13 + 2 * 4);
  FamilyStorage<int> s(1);
  s.fill(0, 1, {0, 0, 0});
  EXPECT_EQ(unbroken_bonds(s.arrays(), 0), 0);
  double buf[1 + kFamilyAtomScalars];
  EXPECT_EQ(pack_family(s.arrays(), 0, buf), family_record_size(0));
  EXPECT_EQ(buf[0], 0.0);
}

TEST(FamilyRecords, ExchangeLayoutFieldByField)
{
  FamilyStorage<int64_t> s(1);
  const int64_t big = (int64_t(1) << 53) + 3;
  s.fill(0, 41, {big, 0, 9});
  double buf[32];
  const int m = pack_family(s.arrays(), 0, buf);
  ASSERT_EQ(m, 1 + 2 * 2 + 13);
  EXPECT_EQ(buf[0], 2.0);
  EXPECT_EQ(bits_id<int64_t>(buf[1]), big);
  EXPECT_EQ(buf[2], 0.1);
  EXPECT_EQ(bits_id<int64_t>(buf[3]), 9);
  EXPECT_EQ(buf[4], 0.1 * 3);
  for (int k = 0; k < 9; k++) EXPECT_EQ(buf[5 + k], 0.5 + k);
  EXPECT_EQ(buf[14], 1.0);
  EXPECT_EQ(buf[15], 2.5);
  EXPECT_EQ(buf[16], 3.25);
  EXPECT_EQ(bits_id<int64_t>(buf[17]), 41);
}

TEST(FamilyRecords, RoundTripsKeepEveryIdExactly)
{
  round_trip<int>(2147483647);
  round_trip<int64_t>((int64_t(1) << 53) + 1);
  round_trip<int64_t>(INT64_MAX);
}

TEST(FamilyRecords, CopyTakesEverySlotAndClearLeavesNoFamily)
{
  FamilyStorage<int64_t> s(2);
  s.fill(0, 12, {4, 0, 6});
  const auto a = s.arrays();
  copy_family(a, 0, 1);
  ASSERT_EQ(s.npartner[1], 3);
  for (int b = 0; b < 3; b++) {
    EXPECT_EQ(s.partner[1][b], s.partner[0][b]);
    EXPECT_EQ(s.omega[1][b], s.omega[0][b]);
    EXPECT_EQ(s.jlocal[1][b], s.jlocal[0][b]);
  }
  for (int k = 0; k < 9; k++) EXPECT_EQ(s.kinv[1][k], s.kinv[0][k]);
  EXPECT_EQ(s.kregular[1], 1);
  EXPECT_EQ(s.vinit[1], 2.5);
  EXPECT_EQ(s.lamref[1], 3.25);
  EXPECT_EQ(s.owntag[1], 12);

  clear_family(a, 1);
  EXPECT_EQ(s.npartner[1], 0);
  for (int k = 0; k < 9; k++) EXPECT_EQ(s.kinv[1][k], 0.0);
  EXPECT_EQ(s.kregular[1], 0);
  EXPECT_EQ(s.vinit[1], 0.0);
  EXPECT_EQ(s.lamref[1], 0.0);
  EXPECT_EQ(s.owntag[1], 0);
  EXPECT_EQ(s.npartner[0], 3);    // the source row is untouched
}

TEST(FamilyRecords, GlobalRestartRecordLayoutAndVersion)
{
  ReferenceBox box;
  box.periodic[0] = 1;
  box.periodic[2] = 1;
  const double lengths[6] = {10.0, 20.0, 30.0, 0.5, -0.25, 0.125};
  for (int k = 0; k < 6; k++) box.box[k] = lengths[k];
  const int64_t tagmax0 = (int64_t(1) << 53) + 7;
  double g[kFamilyGlobals];
  pack_family_globals(1, 37, box, tagmax0, g);
  const double expected[12] = {2.0, 1.0, 37.0, 1.0, 0.0, 1.0, 10.0, 20.0, 30.0, 0.5, -0.25, 0.125};
  for (int k = 0; k < 12; k++) EXPECT_EQ(g[k], expected[k]) << k;
  EXPECT_EQ(bits_id<int64_t>(g[12]), tagmax0);

  int built = 0, maxpartner = 0;
  ReferenceBox back;
  int64_t tagback = 0;
  ASSERT_TRUE(unpack_family_globals(g, built, maxpartner, back, tagback));
  EXPECT_EQ(built, 1);
  EXPECT_EQ(maxpartner, 37);
  for (int k = 0; k < 3; k++) EXPECT_EQ(back.periodic[k], box.periodic[k]);
  for (int k = 0; k < 6; k++) EXPECT_EQ(back.box[k], box.box[k]);
  EXPECT_EQ(tagback, tagmax0);

  // no families yet: maxpartner is read as at least 1
  pack_family_globals(0, 0, box, 0, g);
  ASSERT_TRUE(unpack_family_globals(g, built, maxpartner, back, tagback));
  EXPECT_EQ(built, 0);
  EXPECT_EQ(maxpartner, 1);

  // another format version is refused and nothing is read
  g[0] = 1.0;
  g[1] = 1.0;
  EXPECT_FALSE(unpack_family_globals(g, built, maxpartner, back, tagback));
  EXPECT_EQ(built, 0);
}
