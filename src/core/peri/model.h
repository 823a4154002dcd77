// The parameters of a peridynamic model: per particle type its material, stabilization and
// bulk modulus; per type pair the horizon, short-range contact and the breaking rule. This is
// the rule object that everything else asks: the force evaluation, the bond families (which
// partners, what weight), the stable time step estimate.

#ifndef PERISISSM_PERI_MODEL_H
#define PERISISSM_PERI_MODEL_H

#include "materials/material.h"
#include "peri/breaking.h"
#include "peri/family.h"

#include <memory>
#include <vector>

namespace PeriSISSM {

class Model {
 public:
  // types are numbered 1 .. ntypes
  void set_ntypes(int ntypes);
  int ntypes() const { return n_ - 1; }

  // Inputs: itype; material (owned from now on); cs >= 0 stabilization factor; bulk modulus K.
  void set_type(int itype, std::unique_ptr<Material> material, double cs, double bulk);
  // Inputs: itype; whether its particles are membranes (vertices of a triangle mesh, whose
  // correspondence works in their tangent plane: membrane/membrane.h). Default: no.
  void set_membrane(int itype, bool membrane);
  // Inputs: itype; whether the stabilization of its bonds penalizes the deviation of the bond's
  // length only (|eta| - |Fbar xi|) instead of the whole vector z = eta - Fbar xi
  // (peri/stabilization.h). A bond uses the length form when both ends' types do and neither
  // is a membrane. Default: no.
  void set_length_deviation(int itype, bool length);
  // Inputs: type pair (set for both orders); horizon; contact on/off; contact stiffness.
  void set_pair(int itype, int jtype, double horizon, bool contact, double kcontact);

  const Material &material(int itype) const { return *types_[itype].material; }
  double cs(int itype) const { return types_[itype].cs; }
  double bulk(int itype) const { return types_[itype].bulk; }
  bool membrane(int itype) const { return types_[itype].membrane; }
  bool any_membrane() const;
  // the bond between particles of types itype and jtype uses the length form
  bool length_bond(int itype, int jtype) const
  {
    return types_[itype].length && types_[jtype].length;
  }
  bool any_length_deviation() const;
  // every type uses the length form (then no type is a membrane)
  bool all_length_deviation() const;
  // the reference normal a particle of type itype passes to update_shape(): its row of
  // fam.normal if the type is a membrane, else null
  const double *reference_normal(const Families &fam, int itype, int i) const
  {
    return (fam.normal && types_[itype].membrane) ? fam.normal[i] : nullptr;
  }
  double horizon(int itype, int jtype) const { return pairs_[itype * n_ + jtype].horizon; }
  bool contact(int itype, int jtype) const { return pairs_[itype * n_ + jtype].contact; }
  double kcontact(int itype, int jtype) const { return pairs_[itype * n_ + jtype].kcontact; }
  BreakingRule &breaking() { return breaking_; }
  const BreakingRule &breaking() const { return breaking_; }
  bool any_stabilization() const;
  bool any_contact() const;

  // weight of a bond of reference length r between particles of types itype, jtype and
  // volumes vi, vj (bond_weight() with the pair's horizon); ti, tj the particles' thicknesses,
  // used for membrane types only
  double bond_weight(double r, int itype, int jtype, double vi, double vj, double ti = 0.0,
                     double tj = 0.0) const;
  // stabilization modulus C of a particle of type itype with a regular K^-1
  // (stabilization_modulus() with the type's Cs and K; membrane_stabilization_modulus() for
  // membranes)
  double stabilization_modulus(int itype, const double Kinv[9]) const;

 private:
  struct Type {
    std::unique_ptr<Material> material;
    double cs = 0.0, bulk = 0.0;
    bool membrane = false;
    bool length = false;    // length form of the stabilization (membranes: never)
  };
  struct Pair {
    double horizon = 0.0, kcontact = 0.0;
    bool contact = false;
  };
  int n_ = 1;
  std::vector<Type> types_;
  std::vector<Pair> pairs_;
  BreakingRule breaking_;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_MODEL_H
