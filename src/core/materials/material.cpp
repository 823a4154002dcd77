// Isotropic hyperelastic material: shared parts and factory.

#include "materials/material.h"

#include "materials/material_linear.h"
#include "materials/material_neohookean.h"
#include "materials/material_stvk.h"

#include <cmath>

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
PrincipalSplit Material::split(const Eigen::Vector3d& s) const
{
  PrincipalSplit out;
  out.phat = principal_stress(s);
  out.c = implicit_coefficient(s);
  out.phat_minus = out.phat - out.c.cwiseProduct(s);
  return out;
}

std::unique_ptr<Material> make_material(const std::string& name, double mu, double lambda)
{
  if (name == LinearMaterial::kName) return std::make_unique<LinearMaterial>(mu, lambda);
  if (name == StVKMaterial::kName) return std::make_unique<StVKMaterial>(mu, lambda);
  if (name == NeoHookeanMaterial::kName) return std::make_unique<NeoHookeanMaterial>(mu, lambda);
  return nullptr;
}

const std::vector<std::string>& material_names()
{
  static const std::vector<std::string> names = {
      LinearMaterial::kName, StVKMaterial::kName, NeoHookeanMaterial::kName};
  return names;
}

std::string material_names_joined()
{
  std::string out;
  for (const std::string& name : material_names()) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

}  // namespace PeriSISSM
