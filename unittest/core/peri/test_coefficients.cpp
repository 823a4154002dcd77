// Coefficients of type pairs: the mixing rule, the contact stiffness, the particle spacing of
// the G0 keyword, and the model a completed table configures.
#include "peri/coefficients.h"

#include <gtest/gtest.h>

#include <cmath>
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
