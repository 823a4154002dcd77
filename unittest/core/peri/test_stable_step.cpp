// The stable explicit time step estimate (peri/stable_step.h): s_i of a volume particle and of
// a membrane from K^-1, the P-wave modulus and C; dt_i = kStableStepSafety sqrt(2 rho / d_i)
// and +infinity without stiffness; d_i summed over the unbroken bonds whose partner is here.
#include "materials/material.h"
#include "peri/stable_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

using namespace PeriSISSM;

TEST(StableStep, StiffnessOfVolumeAndMembraneParticles)
{
  // mu 3, lambda 2: P-wave modulus 8; tr(K^-1) 6
  const auto material = make_material("neohookean", 3.0, 2.0);
  ASSERT_NE(material, nullptr);
  const double kinv[9] = {1.0, 0.3, 0.0, 0.3, 2.0, 0.0, 0.0, 0.0, 3.0};
  EXPECT_DOUBLE_EQ(stable_step_stiffness(*material, kinv, 0.0), 2.0 * 8.0);
  EXPECT_DOUBLE_EQ(stable_step_stiffness(*material, kinv, 5.0), 2.0 * 8.0 + 2.5);
  // a membrane's kappa is the mean over its plane: tr / 2
  EXPECT_DOUBLE_EQ(stable_step_stiffness(*material, kinv, 5.0, true), 3.0 * 8.0 + 2.5);
}

TEST(StableStep, TimeStepFromDensityAndStiffness)
{
  EXPECT_DOUBLE_EQ(stable_time_step(2.0, 1.0), kStableStepSafety * 2.0);
  EXPECT_DOUBLE_EQ(stable_time_step(8.0, 4.0), stable_time_step(2.0, 1.0));
  // four times the stiffness: half the step
  EXPECT_DOUBLE_EQ(stable_time_step(2.0, 4.0), 0.5 * stable_time_step(2.0, 1.0));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(stable_time_step(2.0, 0.0), inf);
  EXPECT_EQ(stable_time_step(2.0, -1.0), inf);
}

TEST(StableStep, CouplingSumsTheUnbrokenBondsWhosePartnerIsHere)
{
  // row 1 with partners 7 (row 0), 0 (broken), 9 (row 3), 12 (not here), 2^40 (row 2)
  const int64_t big = int64_t(1) << 40;
  const int64_t partner[5] = {7, 0, 9, 12, big};
  const double omega[5] = {0.5, 100.0, 0.25, 100.0, 2.0};
  const double s[4] = {1.0, 3.0, 5.0, 7.0};
  const std::map<int64_t, int> here = {{7, 0}, {9, 3}, {big, 2}};
  int calls = 0;
  const auto locate = [&](int64_t id) {
    calls++;
    const auto it = here.find(id);
    return it == here.end() ? -1 : it->second;
  };
  const double d = stable_step_coupling(5, partner, omega, s, 1, locate);
  EXPECT_DOUBLE_EQ(d, 0.5 * (3.0 + 1.0) + 0.25 * (3.0 + 7.0) + 2.0 * (3.0 + 5.0));
  EXPECT_EQ(calls, 4);    // broken bonds are not looked up
  EXPECT_EQ(stable_step_coupling(0, partner, omega, s, 1, locate), 0.0);
}
