// Plane stress of every model: the thickness stretch s3 = plane_stress_stretch(s1, s2) zeroes
// Phat_3 (or is 0 in the documented collapse of linear and stvk), minimizes W over s3, agrees
// with the default solver, and gives the 3D material's E and nu in uniaxial plane stress at
// small strain (E / (1 - nu) equibiaxially). The default solver on a toy model with a known
// root, including its limits.

#include "materials/material.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using Eigen::Vector3d;
using PeriSISSM::Material;

// In-plane singular values: a 12 x 12 grid of [0.4, 2.5]^2 and 100 seeded random points.
std::vector<std::pair<double, double>> in_plane_points()
{
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) out.emplace_back(0.4 + 2.1 * i / 11.0, 0.4 + 2.1 * j / 11.0);
  std::mt19937_64 rng(2718u);
  for (int i = 0; i < 100; ++i)
    out.emplace_back(PeriSISSMTest::uniform(rng, 0.4, 2.5), PeriSISSMTest::uniform(rng, 0.4, 2.5));
  return out;
}

Vector3d phat(const Material &m, double s1, double s2, double s3)
{
  return m.principal_stress(Vector3d(s1, s2, s3));
}

// Every model with every parameter set of test_helpers.h (xu takes s0 = mu).
struct Model {
  std::string label;
  std::unique_ptr<Material> m;
};

std::vector<Model> all_models()
{
  std::vector<Model> out;
  for (const std::string &name : PeriSISSM::material_names())
    for (const auto &c : PeriSISSMTest::material_cases())
      out.push_back({name + " " + c.label, PeriSISSM::make_material(name, c.mu, c.lambda)});
  return out;
}

// The collapse of linear and stvk (material_linear.cpp, material_stvk.cpp): for lambda > 0 no
// positive root where s1 + s2 (linear) or s1^2 + s2^2 (stvk) >= 3 + 2 mu / lambda.
bool documented_collapse(const Material &m, double s1, double s2)
{
  const std::string name = m.name();
  if (m.lambda() <= 0.0 || (name != "linear" && name != "stvk")) return false;
  const double measure = name == "linear" ? s1 + s2 : s1 * s1 + s2 * s2;
  return measure >= 3.0 + 2.0 * m.mu() / m.lambda();
}

// |Phat_3(s1, s2, s3*)| <= 1e-10 (|Phat_1| + |Phat_2| + mu) with s3* > 0, or s3* = 0 exactly
// in the documented collapse, where Phat_3 > 0 at every sampled s3 > 0 (W decreases to s3 = 0).
TEST(PlaneStress, ThicknessStressVanishes)
{
  for (const Model &model : all_models()) {
    SCOPED_TRACE(model.label);
    const Material &m = *model.m;
    int roots = 0;
    for (const auto &[s1, s2] : in_plane_points()) {
      const double s3 = m.plane_stress_stretch(s1, s2);
      ASSERT_TRUE(std::isfinite(s3)) << s1 << " " << s2;
      ASSERT_GE(s3, 0.0) << s1 << " " << s2;
      EXPECT_EQ(s3 == 0.0, documented_collapse(m, s1, s2)) << s1 << " " << s2 << " " << s3;
      if (s3 > 0.0) {
        const Vector3d p = phat(m, s1, s2, s3);
        EXPECT_LE(std::abs(p(2)), 1e-10 * (std::abs(p(0)) + std::abs(p(1)) + m.mu()))
            << s1 << " " << s2 << " " << s3;
        ++roots;
      } else {
        for (double t : {1e-12, 1e-6, 1e-3, 0.1, 0.5, 1.0, 2.0, 10.0})
          EXPECT_GT(phat(m, s1, s2, t)(2), 0.0) << s1 << " " << s2 << " s3 = " << t;
      }
      if (HasFailure()) return;
    }
    EXPECT_GE(roots, 50);    // both branches are exercised (stvk nu 0.49 collapses at q >= 3.04)
  }
}

// The closed forms (linear, stvk, xu) and the neo-Hookean Newton with analytic slopes agree
// with the base class's default solver (finite-difference slopes) to 1e-12 relative, and both
// give exactly 0 in the collapse. Plus the round-off floor of the root itself, which matters
// only near the collapse (s3 down to ~1e-5 on these points): Phat_3 is known to ~eps times its
// terms, of size ~(1 + s1^2 + s2^2) relative to the stiffness, so the root is fixed only to
// ~eps (1 + s1^2 + s2^2) / s3 (stvk: in s3^2; linear: in s3, less); allowed 4x that (measured
// at most 1/14 of the total allowance over 2e5 random points per model and parameter set).
TEST(PlaneStress, ModelSolversAgreeWithDefaultSolver)
{
  for (const Model &model : all_models()) {
    SCOPED_TRACE(model.label);
    const Material &m = *model.m;
    for (const auto &[s1, s2] : in_plane_points()) {
      const double s3 = m.plane_stress_stretch(s1, s2);
      const double generic = m.Material::plane_stress_stretch(s1, s2);
      const double floor = s3 > 0.0
          ? 4.0 * std::numeric_limits<double>::epsilon() * (1.0 + s1 * s1 + s2 * s2) / s3
          : 0.0;
      EXPECT_NEAR(generic, s3, 1e-12 * s3 + floor) << s1 << " " << s2;
      if (HasFailure()) return;
    }
  }
}

// W(s1, s2, s3) is smallest at s3 = s3* among s3* +- 1e-4 and s3* (1 +- 1/2), over s3 >= 0.
TEST(PlaneStress, EnergyIsMinimalAtThicknessStretch)
{
  for (const Model &model : all_models()) {
    SCOPED_TRACE(model.label);
    const Material &m = *model.m;
    for (const auto &[s1, s2] : in_plane_points()) {
      const double s3 = m.plane_stress_stretch(s1, s2);
      const double W = m.energy(Vector3d(s1, s2, s3));
      for (double t : {s3 - 1e-4, s3 + 1e-4, 0.5 * s3, 1.5 * s3, s3 + 1.0}) {
        if (t < 0.0) continue;
        EXPECT_GE(m.energy(Vector3d(s1, s2, t)), W) << s1 << " " << s2 << " " << s3 << " " << t;
      }
      if (HasFailure()) return;
    }
  }
}

// A free strip stretched by s1 = 1 + eps: s2 from Phat_2(s1, s2, s3(s1, s2)) = 0 by bisection
// on [1 - eps, 1 + eps] (Phat_2 < 0 at the lower end, Poisson's ratio < 1, > 0 at the upper),
// carried to adjacent doubles. Returns {Phat_1 / eps, -(s2 - 1) / eps}.
std::pair<double, double> uniaxial_plane_stress(const Material &m, double eps)
{
  const double s1 = 1.0 + eps;
  const double e = s1 - 1.0;    // exact
  const auto phat2 = [&m, s1](double s2) {
    return phat(m, s1, s2, m.plane_stress_stretch(s1, s2))(1);
  };
  double lo = 1.0 - e, hi = 1.0 + e;
  EXPECT_LT(phat2(lo), 0.0);
  EXPECT_GT(phat2(hi), 0.0);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (phat2(mid) < 0.0 ? lo : hi) = mid;
  }
  const double s2 = 0.5 * (lo + hi);
  return {phat(m, s1, s2, m.plane_stress_stretch(s1, s2))(0) / e, -(s2 - 1.0) / e};
}

// K, G of a typical steel and of a rubber-like solid with nu = 0.45 (G = 1 MPa).
const std::vector<std::pair<std::string, std::pair<double, double>>> &bulk_shear_cases()
{
  static const std::vector<std::pair<std::string, std::pair<double, double>>> cases = {
      {"steel", {160e9, 79e9}},
      {"rubber nu 0.45", {2.0 * 1e6 * 1.45 / (3.0 * 0.1), 1e6}},
  };
  return cases;
}

// Uniaxial plane stress at eps = 1e-7 recovers E = 9KG/(3K + G) and nu = (3K - 2G)/(2(3K + G))
// to 1e-5 relative (the nonlinearity is O(eps) relative, round-off ~1e-9): the membrane has the
// 3D material's constants. For xu (s0 = 8000): E = 2 s0, nu = 0.
TEST(PlaneStress, UniaxialSmallStrainGivesYoungAndPoisson)
{
  const double eps = 1e-7;
  for (const std::string name : {"linear", "stvk", "neohookean"}) {
    for (const auto &[label, kg] : bulk_shear_cases()) {
      SCOPED_TRACE(name + " " + label);
      const auto [K, G] = kg;
      const PeriSISSM::LameParameters lame = PeriSISSM::lame_from_bulk_shear(K, G);
      const auto m = PeriSISSM::make_material(name, lame.mu, lame.lambda);
      const double E = 9.0 * K * G / (3.0 * K + G);
      const double nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
      const auto [E_meas, nu_meas] = uniaxial_plane_stress(*m, eps);
      EXPECT_NEAR(E_meas, E, 1e-5 * E);
      EXPECT_NEAR(nu_meas, nu, 1e-5 * nu);
    }
  }
  const double s0 = 8000.0;
  const auto xu = PeriSISSM::make_material("xu", s0, 0.0);
  const auto [E_meas, nu_meas] = uniaxial_plane_stress(*xu, eps);
  EXPECT_NEAR(E_meas, 2.0 * s0, 1e-5 * 2.0 * s0);
  EXPECT_LE(std::abs(nu_meas), 1e-5);
}

// Equibiaxial plane stress s1 = s2 = 1 + eps: Phat_1 / eps -> E / (1 - nu), the biaxial
// modulus. Exact for the linear model (Phat is linear in s): 1e-12 relative there; 1e-5 (the
// O(eps) nonlinearity) for stvk and neohookean; xu: 2 s0.
TEST(PlaneStress, EquibiaxialSmallStrainGivesBiaxialModulus)
{
  const double eps = 1e-7;
  for (const std::string name : {"linear", "stvk", "neohookean"}) {
    for (const auto &[label, kg] : bulk_shear_cases()) {
      SCOPED_TRACE(name + " " + label);
      const auto [K, G] = kg;
      const PeriSISSM::LameParameters lame = PeriSISSM::lame_from_bulk_shear(K, G);
      const auto m = PeriSISSM::make_material(name, lame.mu, lame.lambda);
      const double E = 9.0 * K * G / (3.0 * K + G);
      const double nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
      const double s = 1.0 + eps, e = s - 1.0;
      const double measured = phat(*m, s, s, m->plane_stress_stretch(s, s))(0) / e;
      EXPECT_NEAR(measured, E / (1.0 - nu), (name == "linear" ? 1e-9 : 1e-5) * E / (1.0 - nu));
    }
  }
  const double s0 = 8000.0, s = 1.0 + eps;
  const auto xu = PeriSISSM::make_material("xu", s0, 0.0);
  EXPECT_NEAR(phat(*xu, s, s, xu->plane_stress_stretch(s, s))(0) / (s - 1.0), 2.0 * s0,
              1e-5 * 2.0 * s0);
}

// Finite, >= 0, and a root wherever positive, also for degenerate and extreme in-plane
// stretches (the default solver and the models' own). A root: the residual bound of
// ThicknessStressVanishes, or, where that is below round-off (s1 = s2 = 1e8: neohookean's
// Phat_3 = mu s3 + g'(J) s1 s2 cancels terms of 1e16 g'(J), and one ulp of s3 moves it by
// ~eps s3 |dPhat_3/ds3| ~ 1), a sign change of Phat_3 within 1e-13 relative of s3.
TEST(PlaneStress, FiniteForExtremeInPlaneStretches)
{
  const std::vector<double> values = {0.0, 1e-8, 1e-3, 0.4, 1.0, 2.5, 1e3, 1e8};
  for (const Model &model : all_models()) {
    SCOPED_TRACE(model.label);
    const Material &m = *model.m;
    for (double s1 : values) {
      for (double s2 : values) {
        for (const double s3 :
             {m.plane_stress_stretch(s1, s2), m.Material::plane_stress_stretch(s1, s2)}) {
          ASSERT_TRUE(std::isfinite(s3)) << s1 << " " << s2;
          EXPECT_GE(s3, 0.0) << s1 << " " << s2;
          if (s3 > 0.0) {
            const Vector3d p = phat(m, s1, s2, s3);
            const bool small = std::abs(p(2)) <= 1e-10 * (std::abs(p(0)) + std::abs(p(1)) + m.mu());
            const bool bracketed = phat(m, s1, s2, s3 * (1.0 - 1e-13))(2) <= 0.0 &&
                phat(m, s1, s2, s3 * (1.0 + 1e-13))(2) >= 0.0;
            EXPECT_TRUE(small || bracketed)
                << s1 << " " << s2 << " " << s3 << ": " << p.transpose();
          }
        }
        if (HasFailure()) return;
      }
    }
  }
}

// A model without a closed form, to exercise the default solver alone: Phat_3 = mu (s3 - a),
// root s3 = a, which the bracket reaches from s3 = 1 in either direction; a <= 0 gives 0 (no
// positive root), a > 1e100 the documented cap 1e100.
class ShiftedRootMaterial : public Material {
 public:
  explicit ShiftedRootMaterial(double a) : Material(1.0, 0.0), a_(a) {}
  const char *name() const override { return "shifted"; }
  double energy(const Vector3d &s) const override
  {
    return 0.5 *
        ((s(0) - 1.0) * (s(0) - 1.0) + (s(1) - 1.0) * (s(1) - 1.0) + (s(2) - a_) * (s(2) - a_));
  }
  Vector3d principal_stress(const Vector3d &s) const override
  {
    return Vector3d(s(0) - 1.0, s(1) - 1.0, s(2) - a_);
  }
  Vector3d implicit_coefficient(const Vector3d &) const override { return Vector3d::Ones(); }

 private:
  double a_;
};

// Converged to 4 ulps of t = ln s3 (the stopping rule), i.e. 4 eps max(1, |ln a|) relative.
TEST(PlaneStress, DefaultSolverFindsKnownRoots)
{
  const double eps = std::numeric_limits<double>::epsilon();
  for (double a : {1e-300, 1e-200, 1e-5, 0.3, 0.7, 1.0, 1.0 + 1e-12, 3.0, 1e50, 9.9e99}) {
    const ShiftedRootMaterial m(a);
    const double s3 = m.plane_stress_stretch(0.8, 1.3);
    EXPECT_NEAR(s3, a, 4.0 * eps * std::max(1.0, std::abs(std::log(a))) * a) << a;
  }
  EXPECT_EQ(ShiftedRootMaterial(0.0).plane_stress_stretch(1.0, 1.0), 0.0);
  EXPECT_EQ(ShiftedRootMaterial(-2.0).plane_stress_stretch(1.0, 1.0), 0.0);
  EXPECT_EQ(ShiftedRootMaterial(1e-310).plane_stress_stretch(1.0, 1.0), 0.0);    // below DBL_MIN
  EXPECT_NEAR(ShiftedRootMaterial(1e120).plane_stress_stretch(1.0, 1.0), 1e100, 1e87);
}

}    // namespace
