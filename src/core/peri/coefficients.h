// The coefficients of pair_coeff per type pair, the mixing of the pairs not given, and the
// Model they configure (doc/pair_peri_nosb.rst).
//
// Each particle uses the material and Cs of its own type (the line I I); the horizon, s00,
// alpha, breaking and contact of a bond come from the line I J, or, for a pair not given,
// from mix_coefficients() of the two types' own lines.

#ifndef PERISISSM_PERI_COEFFICIENTS_H
#define PERISISSM_PERI_COEFFICIENTS_H

#include "materials/moduli.h"
#include "peri/model.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace PeriSISSM {

// Default of pair_coeff's stabilize keyword. Zero-energy modes need a stiff control, and with
// the bond-averaged residual smooth fields hardly feel it (peri/stabilization.h). On the
// brittle impact deck (examples/impact, s00 = 5e-4) Cs >= 1.75 keeps the damage near the
// indenter, while Cs <= 1.5 lets a fragmentation avalanche run through the whole cylinder
// (converged in dt); 2 leaves a margin. Price: the explicit stable time step of an intact sc
// lattice with horizon 3a falls to ~0.6 of peri/lps's (limits measured: Cs 0.1 > 2.8e-7 s,
// 0.5 ~2.6e-7, 1 ~1.9e-7, 2 ~1.5e-7, peri/lps ~2.6e-7 for the impact material and spacing).
constexpr double kDefaultCs = 2.0;

// Default of pair_coeff's deviation keyword (true: length, false: vector): what the
// stabilization of volume particles penalizes (peri/stabilization.h).
constexpr bool kDefaultLengthDeviation = true;

// One line of pair_coeff (with the numbers or with a material file entry).
struct PairCoefficients {
  Moduli moduli;    // model and its two moduli
  double horizon = 0.0;
  double s00 = 0.0;    // critical stretch (with g0 > 0: set from g0 at init)
  double alpha = 0.0;
  double cs = kDefaultCs;                   // stabilization factor
  bool length = kDefaultLengthDeviation;    // deviation keyword: length (true) or vector
  double g0 = 0.0;    // critical energy release rate of the G0 keyword, 0: s00 given
  bool breaks = true;
  bool contact = true;
  bool membrane = false;    // a type property (the line I I)
  bool plate = true;        // bending keyword: plate (true) or hinge; a type property
};

// The coefficients of a type pair I J not given, from the lines I I and J J: the model of
// I I, the means of K and G, the larger horizon, s00 and alpha of the weaker type (the smaller
// s00 among the types whose bonds can break), breaking and contact on if on for either type;
// Cs 0, no G0, no membrane (per-particle and per-type values are taken from I I and J J).
PairCoefficients mix_coefficients(const PairCoefficients &ii, const PairCoefficients &jj);

// Short-range contact stiffness 15 * 18 K / (pi delta^4) of a pair with bulk modulus K (the
// first modulus of its line) and horizon delta.
double contact_stiffness(double bulk, double horizon);

// Particle spacing of type pair (i, j) for the G0 keyword: the mean V^(1/3) of the particles
// of types i and j, or of all particles when there are none of those types.
// Inputs:  sums[2t], sums[2t + 1] the sum of V^(1/3) and the count of the particles of type t
//          (1 <= t <= ntypes), sums[0], sums[1] those of all particles; types i, j.
// Outputs: h; false when there are no particles at all (h untouched).
bool pair_spacing(const std::vector<double> &sums, int i, int j, double &h);

// The sums pair_spacing() takes, of n particles: volumes, types (1 .. ntypes).
// Outputs: sums (2 (ntypes + 1) entries) += those of these particles.
void add_spacing_sums(int n, const double *volume, const int *type, std::vector<double> &sums);

// The coefficients of all type pairs, 1 <= i, j <= ntypes.
class CoefficientTable {
 public:
  // all pairs not given, with default coefficients
  void resize(int ntypes);
  int ntypes() const { return n_ - 1; }

  // the line of pair I J (i <= j)
  void set(int i, int j, const PairCoefficients &c);
  // whether the line of pair i <= j was given (set)
  bool given(int i, int j) const { return given_[i * n_ + j] != 0; }
  PairCoefficients &at(int i, int j) { return c_[i * n_ + j]; }
  const PairCoefficients &at(int i, int j) const { return c_[i * n_ + j]; }

  // every pair i < j not given from mix_coefficients(), then at(j, i) = at(i, j) for i <= j
  void complete();

  bool any_break() const;
  bool any_g0() const;    // a given pair sets its s00 from G0
  bool any_contact() const;
  // of the completed table: the largest horizon; the smallest horizon of the pairs with contact
  // (DBL_MAX when none has contact)
  double largest_horizon() const;
  double smallest_contact_horizon() const;
  // per type t (bend[t], 1 <= t <= ntypes: its bending modulus, 0 none, -1 auto): the factor
  // bending_factor() of its line t t where bend[t] != 0, else 0 (index 0 unused)
  std::vector<double> bending_factors(const std::vector<double> &bend) const;
  // type t is a membrane type (line t t) without bending (bend[t] == 0, or t beyond bend)
  bool unbent_membrane(int t, const std::vector<double> &bend) const;

  // The G0 keyword: in the order i <= j, each given pair with g0 > 0 gets s00 =
  // s00_from_fracture_energy() of its K, G, Cs, horizon and pair_spacing(sums, i, j); log gets a
  // line per pair whose s00 changes. False (bad_i, bad_j: that pair) when a pair has no particles
  // to take the spacing from; the pairs before it are set.
  bool set_s00_from_g0(const std::vector<double> &sums, std::string &log, int &bad_i, int &bad_j);

  // the model of the completed table: per type the material (make_material(moduli)), Cs,
  // bulk_modulus() and membrane flag of the line I I; per pair horizon, contact and
  // contact_stiffness(moduli.k, horizon); the breaking rule from breaks, s00 and alpha
  void configure(Model &model) const;

 private:
  int n_ = 1;
  std::vector<PairCoefficients> c_;
  std::vector<char> given_;
};

// The coefficients in a restart file (pair peri/nosb's section), format version
// kCoefficientsRestartVersion: the version; per type pair i <= j whether its line was given and,
// if so, the model's name with its terminating NUL (an int length first), the flags break,
// contact, membrane, deviation length and bending plate (5 ints) and K, G, horizon, s00, alpha,
// Cs (6 doubles);
// then the bending moduli of the types 1 .. ntypes (bend[1 .. ntypes]). Native sizes and byte
// order.
constexpr int kCoefficientsRestartVersion = 5;
std::string coefficients_restart_bytes(const CoefficientTable &table,
                                       const std::vector<double> &bend);

// Reads such a section through read(destination, nbytes), which gives the next nbytes of it, into
// table (the lines given, for a table resized to ntypes) and bend (resized to ntypes + 1).
// Returns "" or what is wrong with it (another format version, a corrupt model name, a model this
// build does not have), as an error message; reading stops there.
std::string read_coefficients_restart(const std::function<void(void *, std::size_t)> &read,
                                      CoefficientTable &table, std::vector<double> &bend);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_COEFFICIENTS_H
