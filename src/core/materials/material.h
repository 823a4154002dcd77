// Isotropic hyperelastic material on signed singular values: abstract base and factory.
//
// A model defines its strain energy density W(s) of the signed singular values s of
// F = U diag(s) V^T (signed_svd.h), the principal stresses Phat_k = dW/ds_k, and the implicit
// coefficients c_k >= 0 of the SISSM split (doc/theory.rst); the base class solves its
// plane-stress thickness stretch for membranes, which a model may do faster. Adding a model
// touches one header/source pair and the factory in material.cpp.

#ifndef PERISISSM_MATERIAL_H
#define PERISISSM_MATERIAL_H

#include <Eigen/Core>

#include <functional>
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

  // Model name as used in pair_coeff ("linear", "stvk", "neohookean", "xu").
  virtual const char *name() const = 0;

  double mu() const { return mu_; }
  double lambda() const { return lambda_; }

  // Strain energy density W(s).
  // Inputs:  s signed singular values of F (signed_svd convention).
  // Outputs: W (energy per reference volume, stress units); W = 0 at s = (1, 1, 1).
  virtual double energy(const Eigen::Vector3d &s) const = 0;

  // Principal stresses Phat_k = dW/ds_k.
  // Inputs:  s signed singular values.
  // Outputs: Phat (stress units); P(F) = U diag(Phat) V^T.
  virtual Eigen::Vector3d principal_stress(const Eigen::Vector3d &s) const = 0;

  // Implicit coefficients c_k >= 0 (the rule above): Phat_k^+ = c_k s_k.
  // Inputs:  s signed singular values.
  // Outputs: c (stress units), every entry >= 0 and finite.
  virtual Eigen::Vector3d implicit_coefficient(const Eigen::Vector3d &s) const = 0;

  // Principal stresses and their split at s in one call.
  // Inputs:  s signed singular values.
  // Outputs: {phat, c, phat_minus = phat - c .* s}.
  PrincipalSplit split(const Eigen::Vector3d &s) const;

  // Thickness stretch of plane stress: the s3 > 0 at which principal_stress({s1, s2, s3})[2]
  // vanishes, for in-plane singular values s1, s2 > 0 (a membrane whose through-thickness
  // stress is zero: doc/pair_peri_nosb.rst). Where phat3 changes sign once on s3 > 0, from
  // negative to positive (every model of this package), that root is unique and the minimizer
  // of W(s1, s2, s3) over s3 > 0.
  // Inputs:  s1, s2 in-plane singular values (> 0; other finite values are accepted and the
  //          same root is sought).
  // Outputs: s3 > 0 with phat3(s1, s2, s3) = 0 to round-off; never NaN. When phat3 > 0 for
  //          every s3 > 0 (W decreases all the way to s3 = 0: the thickness collapses, which
  //          linear and stvk do under large in-plane stretch with lambda > 0), 0, the minimizer
  //          of W over s3 >= 0. The default is a safeguarded Newton iteration on
  //          phat3(s1, s2, exp(t)) (plane_stress_newton) with finite-difference slopes, usable
  //          by any model; models override it with closed forms or analytic slopes.
  virtual double plane_stress_stretch(double s1, double s2) const;

 protected:
  // One evaluation of phi(t) = phat3(s1, s2, exp(t)) for plane_stress_newton: value and slope
  // dphi/dt (any estimate; a non-finite or non-positive slope makes that step a bisection).
  struct PlaneStressSample {
    double phi;
    double slope;
  };

  // Root of phi(t), t = ln s3, for plane_stress_stretch(): bracketed by expanding from t = 0
  // (s3 = 1) by doubling steps (1, 2, 4, ...) towards the sign that phi(0) asks for, then
  // Newton steps kept inside the bracket, with a bisection whenever a Newton step would leave
  // it or would not halve the previous step (Numerical Recipes' rtsafe). Stops when phi = 0
  // exactly, or when the step or the bracket is within 4 ulps of t (s3 then carries a few ulps
  // of relative error, phi a few ulps of the stress it is made of), or after 200 steps.
  // Inputs:  phi t -> PlaneStressSample; phi itself finite for t in [ln DBL_MIN, ln 1e100]
  //          (a NaN phi counts as positive).
  // Outputs: s3 = exp(t) at the root; 0 when phi(t) >= 0 down to s3 = DBL_MIN (no positive
  //          root: the collapse case above); 1e100 when phi(t) < 0 up to s3 = 1e100 (W would
  //          decrease without bound in s3: no model of this package).
  static double plane_stress_newton(const std::function<PlaneStressSample(double)> &phi);

  double mu_;
  double lambda_;
};

// Factory.
//
// Inputs:  name model name (one of material_names()), mu, lambda Lame constants. The one-
//          parameter model "xu" takes its s0 = mu and ignores lambda (its lambda() is 0).
// Outputs: the model, or nullptr for an unknown name.
std::unique_ptr<Material> make_material(const std::string &name, double mu, double lambda);

// How a model reads the two moduli of pair_coeff: the bulk and shear moduli K and G, or one
// modulus in K's place (xu: s0) with the second number unused.
enum class ModuliForm { BULK_SHEAR, ONE_MODULUS };

// Inputs:  name model name (one of material_names()).
// Outputs: the model's form; BULK_SHEAR for an unknown name.
ModuliForm moduli_form(const std::string &name);

// Names accepted by make_material, in documentation order.
const std::vector<std::string> &material_names();

// The names joined for error messages: "linear, stvk, neohookean, xu".
std::string material_names_joined();

}    // namespace PeriSISSM

#endif    // PERISISSM_MATERIAL_H
