// Building a bond family (fix nosb/family at the first run): partners within the horizon of
// their types (the horizon itself included), neighbor flags masked off, meshes kept apart; the
// stored slots with their weights (volumes, thicknesses of membranes, a periodic image), vinit
// their sum, and a partner at the same position reported by its slot.
#include "family_storage.h"
#include "peri/family_build.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

using namespace PeriSISSM;

namespace {

// types 1 and 2 (2: membranes); horizons 1.0 (1-1), 1.5 (1-2), 2.0 (2-2)
Model two_type_model()
{
  Model m;
  m.set_ntypes(2);
  m.set_membrane(2, true);
  m.set_pair(1, 1, 1.0, false, 0.0);
  m.set_pair(1, 2, 1.5, false, 0.0);
  m.set_pair(2, 2, 2.0, false, 0.0);
  return m;
}

constexpr int kMask = 0x1FFFFFFF;    // LAMMPS's NEIGHMASK

}    // namespace

TEST(FamilyBuild, PartnersWithinTheHorizonOfTheirTypes)
{
  const Model model = two_type_model();
  // rows: 0 (type 1) at the origin; 1 (1) at 0.9; 2 (2) at 1.4; 3 (2) at 1.9 in y; 4 (1) at
  // exactly the horizon 1.0
  const double x[15] = {0, 0, 0, 0.9, 0, 0, 1.4, 0, 0, 0, 1.9, 0, 0, 0, 1.0};
  const int type[5] = {1, 1, 2, 2, 1};
  const int64_t tag[5] = {10, 11, (int64_t(1) << 40), 13, 14};
  const int jlist[4] = {3 | (1 << 30), 2, 1 | (1 << 30), 4};
  std::vector<std::pair<int64_t, int>> partners;
  gather_partners(model, 0, jlist, 4, kMask, x, type, tag, (const int *) nullptr, partners);
  const std::vector<std::pair<int64_t, int>> expected = {{int64_t(1) << 40, 2}, {11, 1}, {14, 4}};
  EXPECT_EQ(partners, expected);

  // row 2 is in another mesh
  const int mesh[5] = {1, 1, 2, 1, 1};
  partners.clear();
  gather_partners(model, 0, jlist, 4, kMask, x, type, tag, mesh, partners);
  const std::vector<std::pair<int64_t, int>> same_mesh = {{11, 1}, {14, 4}};
  EXPECT_EQ(partners, same_mesh);

  // type 2 - type 2: horizon 2.0 reaches row 3 from row 2 (distance sqrt(1.4^2 + 1.9^2) > 2: no)
  partners.clear();
  const int from2[2] = {3, 0};
  gather_partners(model, 2, from2, 2, kMask, x, type, tag, (const int *) nullptr, partners);
  EXPECT_EQ(partners, (std::vector<std::pair<int64_t, int>>{{10, 0}}));
}

TEST(FamilyBuild, StoredSlotsCarryTheWeightsOfTheReferenceBonds)
{
  const Model model = two_type_model();
  // rows: 0 (type 2) at x 9.5; 1 (2) at 0.3 (0.8 away through the periodic x of length 10);
  // 2 (1) at 8.5; 3 (1) at 9.5 + (0, 0.6, 0). Thin membranes: particle sizes (V / t)^(1/2) far
  // above the horizon, so their partial-volume factors are below 1
  const double x0[12] = {9.5, 0, 0, 0.3, 0, 0, 8.5, 0, 0, 9.5, 0.6, 0};
  const int type[4] = {2, 2, 1, 1};
  const double vfrac[4] = {0.5, 0.25, 1.0, 0.75};
  const double thick[4] = {0.001, 0.002, 0.0, 0.0};
  ReferenceBox box;
  box.periodic[0] = 1;
  box.box[0] = box.box[1] = box.box[2] = 10.0;
  const std::vector<std::pair<int, int>> partners = {{3, 1}, {7, 2}, {8, 3}};

  FamilyStorage<int> s(4);
  s.lamref[0] = 9.0;
  EXPECT_EQ(store_family(model, s.arrays(), 0, 42, partners, x0, box, type, vfrac, thick), -1);
  ASSERT_EQ(s.npartner[0], 3);
  const double w[3] = {model.bond_weight(0.8, 2, 2, 0.5, 0.25, 0.001, 0.002),
                       model.bond_weight(1.0, 2, 1, 0.5, 1.0, 0.001, 0.0),
                       model.bond_weight(0.6, 2, 1, 0.5, 0.75, 0.001, 0.0)};
  for (int b = 0; b < 3; b++) {
    EXPECT_EQ(s.partner[0][b], partners[b].first);
    EXPECT_EQ(s.jlocal[0][b], partners[b].second);
    EXPECT_DOUBLE_EQ(s.omega[0][b], w[b]);
    EXPECT_GT(s.omega[0][b], 0.0);
  }
  EXPECT_DOUBLE_EQ(s.vinit[0], w[0] + w[1] + w[2]);
  EXPECT_EQ(s.lamref[0], 0.0);
  EXPECT_EQ(s.owntag[0], 42);

  // without thicknesses the membrane's weight is that of a volume particle of its volume
  const std::vector<std::pair<int, int>> one = {{3, 1}};
  store_family(model, s.arrays(), 0, 42, one, x0, box, type, vfrac, (const double *) nullptr);
  EXPECT_DOUBLE_EQ(s.omega[0][0], model.bond_weight(0.8, 2, 2, 0.5, 0.25));
  EXPECT_NE(s.omega[0][0], w[0]);
}

TEST(FamilyBuild, APartnerAtTheSamePositionIsReportedBySlot)
{
  const Model model = two_type_model();
  const double x0[9] = {0, 0, 0, 0.5, 0, 0, 0, 0, 0};
  const int type[3] = {1, 1, 1};
  const double vfrac[3] = {1.0, 1.0, 1.0};
  const ReferenceBox box;
  const std::vector<std::pair<int, int>> partners = {{2, 1}, {3, 2}};
  FamilyStorage<int> s(3);
  EXPECT_EQ(store_family(model, s.arrays(), 0, 1, partners, x0, box, type, vfrac,
                         (const double *) nullptr),
            1);
}

TEST(FamilyBuild, StoredFamiliesGetTheirShapeTensorsAndAreCounted)
{
  const Model model = two_type_model();
  // row 0 at the origin with partners along x, y, z (regular K); rows 1 and 3 with one partner
  // each, row 2 with none (singular)
  const double x0[12] = {0, 0, 0, 0.9, 0, 0, 0, 0.9, 0, 0, 0, 0.9};
  const int type[4] = {1, 1, 1, 1};
  const int64_t tag[4] = {10, 11, 12, 13};
  const double vfrac[4] = {1.0, 0.5, 0.25, 0.125};
  const ReferenceBox box;
  using Partners = std::vector<std::pair<int64_t, int>>;
  const std::vector<Partners> fam = {{{11, 1}, {12, 2}, {13, 3}}, {{10, 0}}, {}, {{10, 0}}};

  FamilyStorage<int64_t> s(4), t(4);
  const auto view = [](FamilyStorage<int64_t> &f) {
    Families v;
    v.npartner = f.npartner.data();
    v.jlocal = f.jlocal.data();
    v.omega = f.omega.data();
    v.kinv = f.kinv.data();
    v.kregular = f.kregular.data();
    v.lamref = f.lamref.data();
    return v;
  };
  int64_t bonds = 2, singular = 1;    // added to
  const std::pair<int, int> none = {-1, -1};
  EXPECT_EQ(store_families(model, s.arrays(), view(s), fam, tag, x0, box, type, vfrac,
                           (const double *) nullptr, bonds, singular),
            none);
  EXPECT_EQ(bonds, 2 + 5);
  EXPECT_EQ(singular, 1 + 3);

  // the same as storing and shaping each row alone
  for (int i = 0; i < 4; i++) {
    store_family(model, t.arrays(), i, tag[i], fam[i], x0, box, type, vfrac,
                 (const double *) nullptr);
    update_shape(view(t), x0, box, i);
  }
  EXPECT_EQ(s.kregular, t.kregular);
  EXPECT_EQ(s.kregular, (std::vector<int>{1, 0, 0, 0}));
  EXPECT_EQ(s.kinv_data, t.kinv_data);
  EXPECT_EQ(s.lamref, t.lamref);
  EXPECT_EQ(s.omega_data, t.omega_data);
  EXPECT_EQ(s.owntag, (std::vector<int64_t>{10, 11, 12, 13}));
  EXPECT_GT(s.kinv[0][0], 0.0);

  // row 3 moved onto row 1, its partner: reported with the partner's row, rows after it not
  // stored
  const double same[12] = {0, 0, 0, 0.9, 0, 0, 0, 0.9, 0, 0.9, 0, 0};
  const std::vector<Partners> fam2 = {{{11, 1}, {12, 2}}, {{13, 3}}, {}, {{10, 0}}};
  FamilyStorage<int64_t> u(4);
  bonds = singular = 0;
  const std::pair<int, int> at = {1, 3};
  EXPECT_EQ(store_families(model, u.arrays(), view(u), fam2, tag, same, box, type, vfrac,
                           (const double *) nullptr, bonds, singular),
            at);
  EXPECT_EQ(bonds, 2);
  EXPECT_EQ(u.owntag[3], 0);
}
