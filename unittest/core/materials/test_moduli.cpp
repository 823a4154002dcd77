// The moduli of pair_coeff: each model's form, the checks, the small-strain constants they
// give, and the material built from them.
#include "materials/moduli.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <string>

using namespace PeriSISSM;

namespace {

Moduli moduli(const std::string &model, double k, double g)
{
  Moduli m;
  m.model = model;
  m.k = k;
  m.g = g;
  return m;
}

}    // namespace

TEST(Moduli, FormOfEachModel)
{
  EXPECT_EQ(moduli_form("linear"), ModuliForm::BULK_SHEAR);
  EXPECT_EQ(moduli_form("stvk"), ModuliForm::BULK_SHEAR);
  EXPECT_EQ(moduli_form("neohookean"), ModuliForm::BULK_SHEAR);
  EXPECT_EQ(moduli_form("xu"), ModuliForm::ONE_MODULUS);
  EXPECT_EQ(moduli("xu", 1.0, 0.0).form(), ModuliForm::ONE_MODULUS);
}

TEST(Moduli, ChecksInOrder)
{
  EXPECT_EQ(check_moduli(moduli("linear", 1e9, 6e8)), ModuliProblem::NONE);
  EXPECT_EQ(check_moduli(moduli("linear", 0.0, 6e8)), ModuliProblem::BULK_NOT_POSITIVE);
  EXPECT_EQ(check_moduli(moduli("stvk", -1e9, -6e8)), ModuliProblem::BULK_NOT_POSITIVE);
  EXPECT_EQ(check_moduli(moduli("stvk", 1e9, 0.0)), ModuliProblem::SHEAR_NOT_POSITIVE);
  EXPECT_EQ(check_moduli(moduli("neohookean", 1e9, -5e8)), ModuliProblem::SHEAR_NOT_POSITIVE);
  // K > 0, G > 0 give -1 < nu < 1/2 in exact arithmetic; in floating point 3K - 2G rounds to
  // -2G when K is tiny against G, and nu is -1
  EXPECT_EQ(poisson_from_bulk_shear(1e-300, 1e9), -1.0);
  EXPECT_EQ(check_moduli(moduli("linear", 1e-300, 1e9)), ModuliProblem::POISSON_OUT_OF_RANGE);
  // xu: one modulus, the second number is not looked at
  EXPECT_EQ(check_moduli(moduli("xu", 1e6, 0.0)), ModuliProblem::NONE);
  EXPECT_EQ(check_moduli(moduli("xu", 1e6, -1.0)), ModuliProblem::NONE);
  EXPECT_EQ(check_moduli(moduli("xu", 0.0, 1.0)), ModuliProblem::MODULUS_NOT_POSITIVE);
  EXPECT_EQ(check_moduli(moduli("xu", NAN, 1.0)), ModuliProblem::MODULUS_NOT_POSITIVE);
}

TEST(Moduli, IsotropicConversions)
{
  // K = 5/3, G = 1: nu = 1/4, E = 5/2 (E = 2 G (1 + nu) = 3 K (1 - 2 nu))
  const Moduli m = moduli("linear", 5.0 / 3.0, 1.0);
  EXPECT_DOUBLE_EQ(poisson_ratio(m), 0.25);
  EXPECT_DOUBLE_EQ(young_modulus(m), 2.5);
  EXPECT_EQ(bulk_modulus(m), 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(bending_factor(m), 2.5 / (12.0 * (1.0 - 0.0625)));
  // steel-like: the relations hold to round-off
  const double K = 1.59e11, G = 7.75e10;
  const double E = young_from_bulk_shear(K, G), nu = poisson_from_bulk_shear(K, G);
  EXPECT_NEAR(E, 2.0 * G * (1.0 + nu), 1e-15 * E);
  EXPECT_NEAR(E, 3.0 * K * (1.0 - 2.0 * nu), 1e-15 * E);
}

TEST(Moduli, OneModulusConstants)
{
  // xu with s0: mu = s0, lambda = 0, so E = 2 s0, nu = 0, K = 2 s0 / 3
  const Moduli m = moduli("xu", 3.0, 123.0);
  EXPECT_EQ(bulk_modulus(m), 2.0);
  EXPECT_EQ(young_modulus(m), 6.0);
  EXPECT_EQ(poisson_ratio(m), 0.0);
  EXPECT_EQ(bending_factor(m), 0.5);
}

TEST(Moduli, MaterialHasTheLameConstants)
{
  for (const std::string &name : material_names()) {
    const auto mat = make_material(moduli(name, 5.0, 3.0));
    ASSERT_NE(mat, nullptr) << name;
    EXPECT_EQ(std::string(mat->name()), name);
    if (moduli_form(name) == ModuliForm::ONE_MODULUS) {
      EXPECT_EQ(mat->mu(), 5.0) << name;
      EXPECT_EQ(mat->lambda(), 0.0) << name;
    } else {
      EXPECT_EQ(mat->mu(), 3.0) << name;
      EXPECT_EQ(mat->lambda(), 5.0 - 2.0 * 3.0 / 3.0) << name;
    }
  }
  EXPECT_EQ(make_material(moduli("hookean", 1.0, 1.0)), nullptr);
}

// bulk_modulus() is the small-strain bulk modulus of the material that make_material() builds:
// under a uniform stretch s = 1 + e every principal stress is 3 K e + O(e^2)
TEST(Moduli, BulkModulusIsTheMaterialsSmallStrainOne)
{
  const double e = 1e-6;
  for (const std::string &name : material_names()) {
    const Moduli m = moduli(name, 5.0, 3.0);
    const auto mat = make_material(m);
    const Eigen::Vector3d phat = mat->principal_stress(Eigen::Vector3d::Constant(1.0 + e));
    const double K = bulk_modulus(m);
    for (int k = 0; k < 3; k++) EXPECT_NEAR(phat(k) / (3.0 * e), K, 1e-4 * K) << name;
  }
}
