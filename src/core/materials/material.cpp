// Isotropic hyperelastic material: shared parts and factory.

#include "materials/material.h"

#include "materials/material_linear.h"
#include "materials/material_neohookean.h"
#include "materials/material_stvk.h"
#include "materials/material_xu.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace PeriSISSM {

// mu = G; K = lambda + 2 mu / 3  =>  lambda = K - 2G/3.
LameParameters lame_from_bulk_shear(double K, double G)
{
  return {G, K - 2.0 * G / 3.0};
}

bool lame_parameters_admissible(double mu, double lambda)
{
  return std::isfinite(mu) && std::isfinite(lambda) && mu > 0.0 && lambda + 2.0 * mu / 3.0 > 0.0;
}

// phat_minus is computed as phat - c .* s, so phat_plus + phat_minus reproduces phat up to the
// rounding of that one subtraction.
PrincipalSplit Material::split(const Eigen::Vector3d &s) const
{
  PrincipalSplit out;
  out.phat = principal_stress(s);
  out.c = implicit_coefficient(s);
  out.phat_minus = out.phat - out.c.cwiseProduct(s);
  return out;
}

namespace {

  // Bracket limits of plane_stress_newton in t = ln s3: the smallest normal double and 1e100.
  const double kPlaneStressTMin = std::log(std::numeric_limits<double>::min());    // -708.4
  const double kPlaneStressTMax = std::log(1e100);                                 // 230.3
  constexpr int kPlaneStressMaxSteps = 200;

  // Step in t = ln s3 of the central-difference slope of the default plane_stress_stretch():
  // truncation h^2/6 |phi'''| ~ 2e-11 relative to the slope, round-off ~ eps |phat3 terms| / h
  // ~ 2e-11 of the stress scale. An inexact slope only turns Newton's quadratic convergence into
  // a linear one with that ratio; the bracket keeps every step safe.
  constexpr double kPlaneStressFdStep = 1e-5;

}    // namespace

// The bracket [lo, hi] always has phi(lo) < 0 <= phi(hi) (a NaN phi counts as >= 0). The
// Newton/bisection choice is rtsafe's: bisect when the Newton point leaves the bracket, when the
// slope is not positive (phi crosses zero upwards in the bracket), or when |phi / slope| exceeds
// half of the step before last (not converging fast enough).
double Material::plane_stress_newton(const std::function<PlaneStressSample(double)> &phi)
{
  const double eps = std::numeric_limits<double>::epsilon();
  double lo = 0.0, hi = 0.0;
  PlaneStressSample flo{0.0, 0.0}, fhi{0.0, 0.0};
  const PlaneStressSample at_one = phi(0.0);
  if (at_one.phi == 0.0) return 1.0;
  if (at_one.phi < 0.0) {    // the root is above s3 = 1
    lo = 0.0;
    flo = at_one;
    for (double step = 1.0;; step *= 2.0) {
      const double t = std::min(step, kPlaneStressTMax);
      const PlaneStressSample f = phi(t);
      if (f.phi == 0.0) return std::exp(t);
      if (!(f.phi < 0.0)) {
        hi = t;
        fhi = f;
        break;
      }
      lo = t;
      flo = f;
      if (t >= kPlaneStressTMax) return std::exp(kPlaneStressTMax);
    }
  } else {    // below s3 = 1 (or phi(0) is NaN)
    hi = 0.0;
    fhi = at_one;
    for (double step = 1.0;; step *= 2.0) {
      const double t = std::max(-step, kPlaneStressTMin);
      const PlaneStressSample f = phi(t);
      if (f.phi == 0.0) return std::exp(t);
      if (f.phi < 0.0) {
        lo = t;
        flo = f;
        break;
      }
      hi = t;
      fhi = f;
      if (t <= kPlaneStressTMin) return 0.0;
    }
  }

  // Start from the end with the smaller |phi| (the lower end if phi(hi) is NaN).
  const bool from_lo = !(std::abs(fhi.phi) < std::abs(flo.phi));
  double t = from_lo ? lo : hi;
  PlaneStressSample f = from_lo ? flo : fhi;
  double dx_old = hi - lo, dx = dx_old;
  for (int step = 0; step < kPlaneStressMaxSteps; ++step) {
    const double newton = t - f.phi / f.slope;
    dx_old = dx;
    if (f.slope > 0.0 && newton > lo && newton < hi &&
        std::abs(2.0 * f.phi) <= std::abs(dx_old * f.slope)) {
      dx = t - newton;
      t = newton;
    } else {
      dx = 0.5 * (hi - lo);
      t = lo + dx;
    }
    const double ulps = 4.0 * eps * std::max(1.0, std::abs(t));
    if (std::abs(dx) <= ulps) break;
    f = phi(t);
    if (f.phi == 0.0) break;
    if (f.phi < 0.0)
      lo = t;
    else
      hi = t;
    if (hi - lo <= ulps) break;
  }
  return std::exp(t);
}

// phat3 at s3 = exp(t) and its slope by central differences (kPlaneStressFdStep).
double Material::plane_stress_stretch(double s1, double s2) const
{
  const auto phat3 = [this, s1, s2](double t) {
    return principal_stress(Eigen::Vector3d(s1, s2, std::exp(t)))(2);
  };
  return plane_stress_newton([&phat3](double t) {
    const double h = kPlaneStressFdStep;
    return PlaneStressSample{phat3(t), (phat3(t + h) - phat3(t - h)) / (2.0 * h)};
  });
}

std::unique_ptr<Material> make_material(const std::string &name, double mu, double lambda)
{
  if (name == LinearMaterial::kName) return std::make_unique<LinearMaterial>(mu, lambda);
  if (name == StVKMaterial::kName) return std::make_unique<StVKMaterial>(mu, lambda);
  if (name == NeoHookeanMaterial::kName) return std::make_unique<NeoHookeanMaterial>(mu, lambda);
  if (name == XuMaterial::kName) return std::make_unique<XuMaterial>(mu);
  return nullptr;
}

ModuliForm moduli_form(const std::string &name)
{
  return name == XuMaterial::kName ? ModuliForm::ONE_MODULUS : ModuliForm::BULK_SHEAR;
}

const std::vector<std::string> &material_names()
{
  static const std::vector<std::string> names = {LinearMaterial::kName, StVKMaterial::kName,
                                                 NeoHookeanMaterial::kName, XuMaterial::kName};
  return names;
}

std::string material_names_joined()
{
  std::string out;
  for (const std::string &name : material_names()) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

}    // namespace PeriSISSM
