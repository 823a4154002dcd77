// The stable explicit time step estimate (peri/stable_step.h): s_i of a volume particle and of
// a membrane from K^-1, the P-wave modulus and C; dt_i = kStableStepSafety sqrt(2 rho / d_i)
// and +infinity without stiffness; d_i summed over the unbroken bonds whose partner is here;
// the same per row of a model's types (singular rows 0) and over rows of bond slots.
#include "materials/material.h"
#include "peri/model.h"
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

TEST(StableStep, StiffnessesAndTimeStepsOfRows)
{
  // type 1: volume particles (mu 3, lambda 2, Cs 0.5, K 4); type 2: membranes (mu 1, lambda 1)
  Model model;
  model.set_ntypes(2);
  model.set_type(1, make_material("neohookean", 3.0, 2.0), 0.5, 4.0);
  model.set_type(2, make_material("neohookean", 1.0, 1.0), 0.0, 1.0);
  model.set_membrane(2, true);
  const double k0[9] = {1.0, 0.3, 0.0, 0.3, 2.0, 0.0, 0.0, 0.0, 3.0};
  const double k1[9] = {0.5, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0};
  const double *kinv[3] = {k0, k1, k0};
  const int type[3] = {1, 2, 1}, kregular[3] = {1, 1, 0};
  double s[3] = {-1.0, -1.0, -1.0};
  stable_step_stiffnesses(model, 3, type, kinv, kregular, s);
  EXPECT_EQ(s[0], stable_step_stiffness(model.material(1), k0, model.stabilization_modulus(1, k0)));
  EXPECT_GT(model.stabilization_modulus(1, k0), 0.0);
  EXPECT_EQ(s[1],
            stable_step_stiffness(model.material(2), k1, model.stabilization_modulus(2, k1), true));
  EXPECT_DOUBLE_EQ(s[1], 0.5 * 3.0);
  EXPECT_EQ(s[2], 0.0);

  // rows 0 and 1 bonded to each other (IDs 1 and 2), row 2 without bonds
  const int64_t p0[2] = {2, 0}, p1[1] = {1};
  const double w0[2] = {0.25, 9.0}, w1[1] = {0.5};
  const int64_t *partner[3] = {p0, p1, p1};
  const double *omega[3] = {w0, w1, w1};
  const int npartner[3] = {2, 1, 0};
  const double rho[3] = {2.0, 3.0, 4.0};
  const auto locate = [](int64_t id) {
    return (int) id - 1;
  };
  double dt[3];
  stable_time_steps(3, rho, npartner, partner, omega, s, locate, dt);
  EXPECT_EQ(dt[0], stable_time_step(2.0, 0.25 * (s[0] + s[1])));
  EXPECT_EQ(dt[1], stable_time_step(3.0, 0.5 * (s[1] + s[0])));
  EXPECT_EQ(dt[2], std::numeric_limits<double>::infinity());
}
