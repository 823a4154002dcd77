// Coefficients of type pairs: the mixing rule, the contact stiffness, the particle spacing of
// the G0 keyword, the model a completed table configures, and the restart section.
#include "peri/coefficients.h"

#include "peri/breaking.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace PeriSISSM;

namespace {

PairCoefficients line(const char *model, double k, double g, double horizon, double s00,
                      double alpha)
{
  PairCoefficients c;
  c.moduli.model = model;
  c.moduli.k = k;
  c.moduli.g = g;
  c.horizon = horizon;
  c.s00 = s00;
  c.alpha = alpha;
  return c;
}

}    // namespace

TEST(Coefficients, MixingTakesMeansLargerHorizonAndTheWeakerType)
{
  PairCoefficients a = line("linear", 2.0, 1.0, 0.3, 0.01, 0.25);
  PairCoefficients b = line("stvk", 4.0, 3.0, 0.5, 0.02, 0.5);
  a.contact = false;
  a.membrane = b.membrane = true;
  a.g0 = b.g0 = 7.0;
  const PairCoefficients m = mix_coefficients(a, b);
  EXPECT_EQ(m.moduli.model, "linear");
  EXPECT_EQ(m.moduli.k, 3.0);
  EXPECT_EQ(m.moduli.g, 2.0);
  EXPECT_EQ(m.horizon, 0.5);
  EXPECT_EQ(m.s00, 0.01);    // a breaks at the smaller stretch
  EXPECT_EQ(m.alpha, 0.25);
  EXPECT_EQ(m.cs, 0.0);
  EXPECT_EQ(m.g0, 0.0);
  EXPECT_TRUE(m.breaks);
  EXPECT_TRUE(m.contact);    // on for either type
  EXPECT_FALSE(m.membrane);
  // the other order: the same weaker type
  const PairCoefficients r = mix_coefficients(b, a);
  EXPECT_EQ(r.s00, 0.01);
  EXPECT_EQ(r.alpha, 0.25);
  EXPECT_EQ(r.moduli.model, "stvk");
}

TEST(Coefficients, MixingIgnoresTheCriticalStretchOfATypeThatDoesNotBreak)
{
  PairCoefficients a = line("linear", 2.0, 1.0, 0.3, 0.0, 0.0);
  a.breaks = false;
  a.contact = false;
  PairCoefficients b = line("linear", 2.0, 1.0, 0.3, 0.02, 0.5);
  b.contact = false;
  for (const PairCoefficients &m : {mix_coefficients(a, b), mix_coefficients(b, a)}) {
    EXPECT_EQ(m.s00, 0.02);
    EXPECT_EQ(m.alpha, 0.5);
    EXPECT_TRUE(m.breaks);
    EXPECT_FALSE(m.contact);
  }
  b.breaks = false;
  EXPECT_FALSE(mix_coefficients(a, b).breaks);
}

TEST(Coefficients, ContactStiffness)
{
  // 15 * 18 K / (pi delta^4)
  EXPECT_DOUBLE_EQ(contact_stiffness(M_PI, 1.0), 270.0);
  EXPECT_DOUBLE_EQ(contact_stiffness(1e9, 0.003), 270.0 * 1e9 / (M_PI * std::pow(0.003, 4)));
  EXPECT_DOUBLE_EQ(contact_stiffness(1.0, 2.0), contact_stiffness(1.0, 1.0) / 16.0);
}

TEST(Coefficients, PairSpacing)
{
  // types 1 and 2: V^(1/3) sums 3 over 2 particles, 10 over 4; type 3 none
  const std::vector<double> sums = {13.0, 6.0, 3.0, 2.0, 10.0, 4.0, 0.0, 0.0};
  double h = -1.0;
  ASSERT_TRUE(pair_spacing(sums, 1, 1, h));
  EXPECT_EQ(h, 1.5);
  ASSERT_TRUE(pair_spacing(sums, 1, 2, h));
  EXPECT_EQ(h, 13.0 / 6.0);
  ASSERT_TRUE(pair_spacing(sums, 1, 3, h));
  EXPECT_EQ(h, 1.5);
  ASSERT_TRUE(pair_spacing(sums, 3, 3, h));    // none of the type: all particles
  EXPECT_EQ(h, 13.0 / 6.0);
  const std::vector<double> empty(8, 0.0);
  h = -1.0;
  EXPECT_FALSE(pair_spacing(empty, 2, 3, h));
  EXPECT_EQ(h, -1.0);
}

// the sums of V^(1/3) and counts per type and of all particles, added to what is there
TEST(Coefficients, SpacingSumsPerTypeAndOfAll)
{
  const double volume[3] = {8.0, 27.0, 1.0};
  const int type[3] = {2, 1, 2};
  std::vector<double> sums(6, 0.0);
  sums[0] = 1.0;
  add_spacing_sums(3, volume, type, sums);
  const std::vector<double> expected = {7.0, 3.0, 3.0, 1.0, 3.0, 2.0};
  for (int k = 0; k < 6; k++) EXPECT_NEAR(sums[k], expected[k], 1e-15 * expected[k]) << k;
}

TEST(Coefficients, TableMixesThePairsNotGivenAndMirrors)
{
  CoefficientTable t;
  t.resize(3);
  t.set(1, 1, line("linear", 2.0, 1.0, 0.3, 0.01, 0.25));
  t.set(2, 2, line("neohookean", 4.0, 3.0, 0.5, 0.02, 0.5));
  t.set(3, 3, line("xu", 6.0, 0.0, 0.4, 0.03, 0.0));
  t.set(1, 3, line("stvk", 9.0, 8.0, 0.7, 0.05, 0.1));
  EXPECT_TRUE(t.given(1, 3));
  EXPECT_FALSE(t.given(1, 2));
  t.complete();
  EXPECT_EQ(t.at(1, 2).moduli.k, 3.0);
  EXPECT_EQ(t.at(1, 2).horizon, 0.5);
  EXPECT_EQ(t.at(2, 1).horizon, 0.5);
  EXPECT_EQ(t.at(1, 3).moduli.model, "stvk");    // given: kept
  EXPECT_EQ(t.at(3, 1).horizon, 0.7);
  EXPECT_EQ(t.at(2, 3).s00, 0.02);
  EXPECT_EQ(t.at(3, 2).s00, 0.02);
  EXPECT_TRUE(t.any_break());
  EXPECT_TRUE(t.any_contact());
  EXPECT_FALSE(t.any_g0());
  PairCoefficients g = line("linear", 2.0, 1.0, 0.3, 0.0, 0.25);
  g.g0 = 3.0;
  t.set(2, 3, g);
  EXPECT_TRUE(t.any_g0());
}

TEST(Coefficients, TableConfiguresTheModel)
{
  CoefficientTable t;
  t.resize(2);
  PairCoefficients one = line("linear", 5.0, 3.0, 0.3, 0.01, 0.25);
  one.cs = 1.5;
  one.contact = false;
  PairCoefficients two = line("xu", 6.0, 0.0, 0.5, 0.02, 0.0);
  two.membrane = true;
  two.breaks = false;
  t.set(1, 1, one);
  t.set(2, 2, two);
  t.complete();
  EXPECT_TRUE(t.any_break());
  Model model;
  t.configure(model);
  ASSERT_EQ(model.ntypes(), 2);
  EXPECT_EQ(std::string(model.material(1).name()), "linear");
  EXPECT_EQ(model.material(1).mu(), 3.0);
  EXPECT_EQ(model.material(1).lambda(), 3.0);
  EXPECT_EQ(model.bulk(1), 5.0);
  EXPECT_EQ(model.cs(1), 1.5);
  EXPECT_FALSE(model.membrane(1));
  EXPECT_EQ(std::string(model.material(2).name()), "xu");
  EXPECT_EQ(model.material(2).mu(), 6.0);
  EXPECT_EQ(model.bulk(2), 4.0);    // 2 s0 / 3
  EXPECT_EQ(model.cs(2), kDefaultCs);
  EXPECT_TRUE(model.membrane(2));
  EXPECT_EQ(model.horizon(1, 2), 0.5);
  EXPECT_EQ(model.horizon(2, 1), 0.5);
  EXPECT_FALSE(model.contact(1, 1));
  EXPECT_TRUE(model.contact(1, 2));
  EXPECT_EQ(model.kcontact(2, 2), contact_stiffness(6.0, 0.5));
  EXPECT_EQ(model.kcontact(1, 2), contact_stiffness(5.5, 0.5));
  // breaking: pair 1 1 breaks above s00 = 0.01, pair 2 2 never, the mixed pair with type 1's
  const BreakingRule &rule = model.breaking();
  EXPECT_TRUE(rule.any());
  EXPECT_FALSE(rule.uniform());
  const auto breaks = [&rule](double stretch, int i, int j) {
    double acc = 1.0, den = 1.0;
    const double r2 = (1.0 + stretch) * (1.0 + stretch);
    return rule.check<BreakingRule::BREAK, 0>(r2, 1.0, i, j, 0.0, acc, den);
  };
  EXPECT_FALSE(breaks(0.009, 1, 1));
  EXPECT_TRUE(breaks(0.011, 1, 1));
  EXPECT_FALSE(breaks(0.5, 2, 2));
  EXPECT_TRUE(breaks(0.011, 2, 1));
  EXPECT_FALSE(breaks(0.009, 1, 2));
}

namespace {

// a reader of bytes from the start of a string (past its end: throws)
std::function<void(void *, std::size_t)> reader(const std::string &bytes, std::size_t &at)
{
  return [&bytes, &at](void *dst, std::size_t n) {
    if (at + n > bytes.size()) throw std::out_of_range("read past the section");
    bytes.copy(static_cast<char *>(dst), n, at);
    at += n;
  };
}

}    // namespace

// the given lines and the bending moduli come back field by field, the lines not given stay
// not given, and the section is read to its last byte
TEST(Coefficients, RestartSectionKeepsTheGivenLines)
{
  CoefficientTable table;
  table.resize(3);
  PairCoefficients a = line("neohookean", 3.0, 2.0, 0.4, 0.02, 0.3);
  a.cs = 1.5;
  a.breaks = false;
  a.membrane = true;
  PairCoefficients b = line("xu", 6.0, 0.0, 0.5, 0.01, 0.0);
  b.contact = false;
  b.length = !kDefaultLengthDeviation;
  b.plate = !PairCoefficients{}.plate;    // the non-default bending
  table.set(1, 1, a);
  table.set(2, 3, b);
  const std::vector<double> bend = {0.0, 2.5, 0.0, -1.0};
  const std::string bytes = coefficients_restart_bytes(table, bend);
  EXPECT_EQ(bytes.size(),
            7 * sizeof(int) + 2 * (6 * sizeof(int) + 6 * sizeof(double)) + sizeof("neohookean") +
                sizeof("xu") + 3 * sizeof(double));

  CoefficientTable back;
  back.resize(3);
  std::vector<double> bend_back;
  std::size_t at = 0;
  EXPECT_EQ(read_coefficients_restart(reader(bytes, at), back, bend_back), "");
  EXPECT_EQ(at, bytes.size());
  EXPECT_EQ(bend_back, bend);
  for (int i = 1; i <= 3; i++)
    for (int j = i; j <= 3; j++) EXPECT_EQ(back.given(i, j), table.given(i, j)) << i << j;
  for (const auto &ij : {std::make_pair(1, 1), std::make_pair(2, 3)}) {
    const PairCoefficients &c = table.at(ij.first, ij.second);
    const PairCoefficients &r = back.at(ij.first, ij.second);
    EXPECT_EQ(r.moduli.model, c.moduli.model);
    EXPECT_EQ(r.plate, c.plate);
    EXPECT_EQ(r.moduli.k, c.moduli.k);
    EXPECT_EQ(r.moduli.g, c.moduli.g);
    EXPECT_EQ(r.horizon, c.horizon);
    EXPECT_EQ(r.s00, c.s00);
    EXPECT_EQ(r.alpha, c.alpha);
    EXPECT_EQ(r.cs, c.cs);
    EXPECT_EQ(r.breaks, c.breaks);
    EXPECT_EQ(r.contact, c.contact);
    EXPECT_EQ(r.membrane, c.membrane);
    EXPECT_EQ(r.length, c.length);
  }
}

// another format version, a corrupt name length and an unknown model stop the reading there
TEST(Coefficients, RestartSectionProblemsAreNamed)
{
  CoefficientTable table;
  table.resize(1);
  table.set(1, 1, line("linear", 2.0, 1.0, 0.3, 0.01, 0.25));
  const std::string good = coefficients_restart_bytes(table, {0.0, 0.0});
  std::vector<double> bend;
  std::size_t at = 0;

  std::string old = good;
  const int two = 2;
  old.replace(0, sizeof(int), reinterpret_cast<const char *>(&two), sizeof(int));
  EXPECT_NE(read_coefficients_restart(reader(old, at), table, bend)
                .find("format version 2, this build reads version 5"),
            std::string::npos);
  EXPECT_EQ(at, sizeof(int));

  std::string corrupt = good;
  const int huge = 100000;
  corrupt.replace(2 * sizeof(int), sizeof(int), reinterpret_cast<const char *>(&huge), sizeof(int));
  at = 0;
  EXPECT_NE(read_coefficients_restart(reader(corrupt, at), table, bend)
                .find("corrupt (model name of 100000 chars)"),
            std::string::npos);

  std::string unknown = good;
  unknown.replace(3 * sizeof(int), 6, "lineax");
  at = 0;
  EXPECT_NE(read_coefficients_restart(reader(unknown, at), table, bend)
                .find("names model 'lineax', which this build does not have"),
            std::string::npos);
}

TEST(Coefficients, HorizonsOfTheCompletedTable)
{
  CoefficientTable t;
  t.resize(3);
  t.set(1, 1, line("linear", 2.0, 1.0, 0.3, 0.01, 0.25));
  t.set(2, 2, line("linear", 2.0, 1.0, 0.5, 0.01, 0.25));
  PairCoefficients c = line("linear", 2.0, 1.0, 0.2, 0.01, 0.25);
  c.contact = false;
  t.set(3, 3, c);
  c.horizon = 0.9;
  t.set(1, 3, c);    // the largest horizon, without contact
  t.complete();
  EXPECT_EQ(t.largest_horizon(), 0.9);
  EXPECT_EQ(t.smallest_contact_horizon(), 0.3);
  for (int i = 1; i <= 3; i++)
    for (int j = 1; j <= 3; j++) t.at(i, j).contact = false;
  EXPECT_EQ(t.smallest_contact_horizon(), DBL_MAX);
}

TEST(Coefficients, BendingFactorsAndUnbentMembranes)
{
  CoefficientTable t;
  t.resize(3);
  PairCoefficients m = line("linear", 2.0, 1.0, 0.3, 0.01, 0.25);
  m.membrane = true;
  t.set(1, 1, m);
  t.set(2, 2, line("neohookean", 4.0, 3.0, 0.5, 0.02, 0.5));
  t.set(3, 3, m);
  t.complete();
  const std::vector<double> bend = {0.0, -1.0, 0.0, 2.5};
  const std::vector<double> f = t.bending_factors(bend);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[1], bending_factor(t.at(1, 1).moduli));
  EXPECT_GT(f[1], 0.0);
  EXPECT_EQ(f[2], 0.0);
  EXPECT_EQ(f[3], bending_factor(t.at(3, 3).moduli));
  for (int type = 1; type <= 3; type++) EXPECT_FALSE(t.unbent_membrane(type, bend)) << type;
  EXPECT_TRUE(t.unbent_membrane(3, {0.0, -1.0, 0.0, 0.0}));
  EXPECT_FALSE(t.unbent_membrane(2, {0.0, -1.0, 0.0, 0.0}));    // not a membrane
  EXPECT_TRUE(t.unbent_membrane(3, {0.0, -1.0}));    // type 3 beyond the list: no bending
}

TEST(Coefficients, CriticalStretchFromFractureEnergy)
{
  CoefficientTable t;
  t.resize(2);
  PairCoefficients g = line("linear", 2.0, 1.0, 0.3, 0.0, 0.25);
  g.g0 = 5.0;
  t.set(1, 1, g);
  t.set(2, 2, line("linear", 2.0, 1.0, 0.3, 0.01, 0.25));
  // type 1: 4 particles of V^(1/3) sum 0.4 (h = 0.1); type 2: none
  std::vector<double> sums = {0.4, 4.0, 0.4, 4.0, 0.0, 0.0};
  std::string log;
  int bi = 0, bj = 0;
  ASSERT_TRUE(t.set_s00_from_g0(sums, log, bi, bj));
  const double s00 =
      s00_from_fracture_energy(5.0, 2.0, 1.0, kDefaultCs, 0.3, 0.1, kDefaultLengthDeviation);
  EXPECT_EQ(t.at(1, 1).s00, s00);
  EXPECT_EQ(t.at(2, 2).s00, 0.01);    // given without G0: kept
  EXPECT_NE(log.find("types 1 1: G0 = 5 gives s00 = "), std::string::npos) << log;
  EXPECT_NE(log.find("horizon = 0.3 = 3 h)\n"), std::string::npos) << log;
  log.clear();
  ASSERT_TRUE(t.set_s00_from_g0(sums, log, bi, bj));
  EXPECT_EQ(log, "");    // unchanged: not logged again
  // no particles at all: the pair is named
  g.g0 = 7.0;
  t.set(1, 2, g);
  sums.assign(6, 0.0);
  EXPECT_FALSE(t.set_s00_from_g0(sums, log, bi, bj));
  EXPECT_EQ(bi, 1);
  EXPECT_EQ(bj, 1);
}
