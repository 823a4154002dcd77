// The method's scalar example x = (x - 2)^2: plain successive substitution fails, the split
// (semi-implicit) substitution converges to the root in [0, 1].

#include "scalar_substitution.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using PeriSISSM::iterate;
using PeriSISSM::split_map;
using PeriSISSM::talk_example_map;

TEST(ScalarSubstitution, IterateRecordsAllIterates)
{
  const auto xs = iterate(
      [](double x) {
        return 2.0 * x;
      },
      1.0, 4);
  ASSERT_EQ(xs.size(), 5u);
  EXPECT_EQ(xs[4], 16.0);
  EXPECT_EQ(iterate(talk_example_map, 0.5, 0).size(), 1u);
}

// Plain substitution: x^1 = 2.25, x^2 = 0.0625, ... It leaves [0, 1] at once and, both fixed points
// (1 and 4) being repelling (|g'| = 2 and 4), wanders in [0, 4] without converging.
TEST(ScalarSubstitution, PlainSubstitutionDoesNotConverge)
{
  const auto xs = iterate(talk_example_map, 0.5, 100);
  EXPECT_DOUBLE_EQ(xs[1], 2.25);
  EXPECT_DOUBLE_EQ(xs[2], 0.0625);
  EXPECT_GT(xs[1], 1.0);    // leaves [0, 1]
  double late_step = 0.0;
  for (int k = 90; k < 100; ++k) late_step = std::max(late_step, std::abs(xs[k + 1] - xs[k]));
  EXPECT_GT(late_step, 1e-3);
  EXPECT_GT(std::abs(xs.back() - 1.0), 1e-6);
}

// The split map with the example's implicit coefficient is (x^2 + 4)/5, a contraction on [0, 1]
// (slope 2x/5 <= 0.4) with fixed point 1, the root of x = (x - 2)^2 there.
TEST(ScalarSubstitution, SplitSubstitutionConvergesToRoot)
{
  const auto g = split_map(talk_example_map, PeriSISSM::kTalkExampleImplicit);
  for (double x : {0.0, 0.3, 0.5, 1.0, 2.5})
    EXPECT_NEAR(g(x), (x * x + 4.0) / 5.0, 1e-15 * (1 + x * x));
  const auto xs = iterate(g, 0.5, 100);
  for (double x : xs) {
    EXPECT_GE(x, 0.0);
    EXPECT_LE(x, 1.0);
  }
  EXPECT_NEAR(xs.back(), 1.0, 1e-12);
  EXPECT_NEAR(talk_example_map(xs.back()), xs.back(), 1e-12);
}

// The split does not move fixed points: any a >= 0 keeps x = 1 fixed; a too small to absorb the
// -4x slope (here a = 0.2: slope (2x - 4 + 0.2)/1.2 = -1.5 at x = 1) still fails.
TEST(ScalarSubstitution, SplitKeepsFixedPointsAndNeedsEnoughImplicitPart)
{
  for (double a : {0.0, 0.5, 4.0, 10.0}) EXPECT_DOUBLE_EQ(split_map(talk_example_map, a)(1.0), 1.0);
  const auto weak = iterate(split_map(talk_example_map, 0.2), 0.5, 100);
  EXPECT_GT(std::abs(weak.back() - 1.0), 1e-6);
}

}    // namespace
