// The two moduli pair_coeff gives a type's material, and the elastic constants they set.
//
// A model of form BULK_SHEAR (linear, stvk, neohookean) takes the bulk and shear moduli K and
// G; a model of form ONE_MODULUS (xu) takes its one modulus s0 in K's place and ignores the
// second number. Small-strain constants of xu: mu = s0, lambda = 0, so E = 2 s0, nu = 0 and
// K = 2 s0 / 3 (materials/material_xu.h).

#ifndef PERISISSM_MATERIALS_MODULI_H
#define PERISISSM_MATERIALS_MODULI_H

#include "materials/material.h"

#include <memory>
#include <string>

namespace PeriSISSM {

struct Moduli {
  std::string model;    // one of material_names()
  double k = 0.0;       // K (ONE_MODULUS: the model's one modulus)
  double g = 0.0;       // G (ONE_MODULUS: not used)

  ModuliForm form() const { return moduli_form(model); }
};

// Poisson's ratio and Young's modulus of an isotropic material.
// Inputs:  K bulk modulus, G shear modulus.
// Outputs: nu = (3K - 2G) / (2 (3K + G)); E = 9 K G / (3K + G).
double poisson_from_bulk_shear(double K, double G);
double young_from_bulk_shear(double K, double G);

// What is wrong with a pair of moduli, checked in this order (the first that applies).
enum class ModuliProblem {
  NONE,
  MODULUS_NOT_POSITIVE,    // ONE_MODULUS with k <= 0 (or NaN)
  BULK_NOT_POSITIVE,       // BULK_SHEAR with K <= 0
  SHEAR_NOT_POSITIVE,      // BULK_SHEAR with G <= 0
  POISSON_OUT_OF_RANGE     // BULK_SHEAR with nu outside (-1, 0.5) in floating point, or Lame
                           // constants not admissible (lame_parameters_admissible)
};
ModuliProblem check_moduli(const Moduli &m);

// Small-strain constants of the material.
// Outputs: K (ONE_MODULUS: 2 s0 / 3); E and nu (ONE_MODULUS: 2 s0 and 0).
double bulk_modulus(const Moduli &m);
double young_modulus(const Moduli &m);
double poisson_ratio(const Moduli &m);

// Plate bending stiffness per cubed thickness, E / (12 (1 - nu^2)): D = that times t^3.
double bending_factor(const Moduli &m);

// The material model: make_material(model, mu, lambda) with the Lame constants of K and G
// (lame_from_bulk_shear), or with mu = s0 for ONE_MODULUS. Null for an unknown model.
std::unique_ptr<Material> make_material(const Moduli &m);

}    // namespace PeriSISSM

#endif    // PERISISSM_MATERIALS_MODULI_H
