// Isotropic hyperelastic material on signed singular values: abstract base and factory.
//
// A model defines its strain energy density W(s) of the signed singular values s of
// F = U diag(s) V^T (signed_svd.h), the principal stresses Phat_k = dW/ds_k, and the implicit
// coefficients c_k >= 0 of the SISSM split (doc/theory.rst). Adding a model touches one
// header/source pair and the factory in material.cpp.

#ifndef PERISISSM_MATERIAL_H
#define PERISISSM_MATERIAL_H

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace PeriSISSM {

// Lame constants of an isotropic material.
struct LameParameters {
  double mu;
  double lambda;
};

// Lame constants from bulk and shear modulus, as in pair_coeff (doc/pair_peri_nosb.rst).
//
// Inputs:  K bulk modulus, G shear modulus (stress units).
// Outputs: mu = G, lambda = K - 2G/3 (negative for Poisson's ratio < 0).
LameParameters lame_from_bulk_shear(double K, double G);

// Whether (mu, lambda) describe a stable isotropic material: G = mu > 0 and
// K = lambda + 2 mu / 3 > 0 (equivalently -1 < nu < 1/2).
//
// Inputs:  mu, lambda Lame constants.
// Outputs: true when both conditions hold (and both are finite).
bool lame_parameters_admissible(double mu, double lambda);

// The split of the principal stresses at one state s (doc/theory.rst):
// phat = dW/ds, c >= 0 the implicit coefficients, phat_minus = phat - c .* s (explicit part).
// The implicit part is phat_plus = c .* s; phat_plus + phat_minus == phat up to one rounding.
struct PrincipalSplit {
  Eigen::Vector3d phat;
  Eigen::Vector3d c;
  Eigen::Vector3d phat_minus;
};

// Abstract isotropic hyperelastic material.
//
// Rule for the implicit coefficients (documented per model): write Phat_k as the sum of the
// terms that come out of dW/ds_k, each term grouped by its physical origin (shear part,
// volumetric part). A term goes into c_k s_k when it has the form a * s_k with a >= 0 for every
// state, i.e. it grows with s_k at any s; every other term is explicit. A model whose Phat_k is
// linear in s_k collects the coefficient of s_k first (linear: 2 mu + lambda = K + 4G/3 > 0).
// Then c_k >= 0 and Phat_k^+ = c_k s_k is the restoring part that SISSM treats implicitly.
class Material {
 public:
  // Inputs: mu, lambda Lame constants (stress units). Not validated here: see
  // lame_parameters_admissible(); every model stays finite for any finite values.
  Material(double mu, double lambda) : mu_(mu), lambda_(lambda) {}
  virtual ~Material() = default;

  // Model name as used in pair_coeff ("linear", "stvk", "neohookean").
  virtual const char* name() const = 0;

  double mu() const { return mu_; }
  double lambda() const { return lambda_; }

  // Strain energy density W(s).
  // Inputs:  s signed singular values of F (signed_svd convention).
  // Outputs: W (energy per reference volume, stress units); W = 0 at s = (1, 1, 1).
  virtual double energy(const Eigen::Vector3d& s) const = 0;

  // Principal stresses Phat_k = dW/ds_k.
  // Inputs:  s signed singular values.
  // Outputs: Phat (stress units); P(F) = U diag(Phat) V^T.
  virtual Eigen::Vector3d principal_stress(const Eigen::Vector3d& s) const = 0;

  // Implicit coefficients c_k >= 0 (the rule above): Phat_k^+ = c_k s_k.
  // Inputs:  s signed singular values.
  // Outputs: c (stress units), every entry >= 0 and finite.
  virtual Eigen::Vector3d implicit_coefficient(const Eigen::Vector3d& s) const = 0;

  // Principal stresses and their split at s in one call.
  // Inputs:  s signed singular values.
  // Outputs: {phat, c, phat_minus = phat - c .* s}.
  PrincipalSplit split(const Eigen::Vector3d& s) const;

 protected:
  double mu_;
  double lambda_;
};

// Factory.
//
// Inputs:  name model name (one of material_names()), mu, lambda Lame constants.
// Outputs: the model, or nullptr for an unknown name.
std::unique_ptr<Material> make_material(const std::string& name, double mu, double lambda);

// Names accepted by make_material, in documentation order.
const std::vector<std::string>& material_names();

// The names joined for error messages: "linear, stvk, neohookean".
std::string material_names_joined();

}  // namespace PeriSISSM

#endif  // PERISISSM_MATERIAL_H
