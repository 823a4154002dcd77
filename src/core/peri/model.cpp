// Model parameters (see model.h).

#include "peri/model.h"

#include "membrane/membrane.h"
#include "peri/family.h"
#include "peri/stabilization.h"

namespace PeriSISSM {

void Model::set_ntypes(int ntypes)
{
  n_ = ntypes + 1;
  types_.clear();
  types_.resize(n_);
  pairs_.assign(n_ * n_, Pair());
}

void Model::set_type(int itype, std::unique_ptr<Material> material, double cs, double bulk)
{
  types_[itype].material = std::move(material);
  types_[itype].cs = cs;
  types_[itype].bulk = bulk;
}

void Model::set_membrane(int itype, bool membrane)
{
  types_[itype].membrane = membrane;
  if (membrane) types_[itype].length = false;
}

void Model::set_length_deviation(int itype, bool length)
{
  types_[itype].length = length && !types_[itype].membrane;
}

void Model::set_pair(int itype, int jtype, double horizon, bool contact, double kcontact)
{
  for (int k = 0; k < 2; k++) {
    Pair &p = k ? pairs_[jtype * n_ + itype] : pairs_[itype * n_ + jtype];
    p.horizon = horizon;
    p.contact = contact;
    p.kcontact = kcontact;
  }
}

bool Model::any_stabilization() const
{
  for (int i = 1; i < n_; i++)
    if (types_[i].cs > 0.0) return true;
  return false;
}

bool Model::any_membrane() const
{
  for (int i = 1; i < n_; i++)
    if (types_[i].membrane) return true;
  return false;
}

bool Model::any_length_deviation() const
{
  for (int i = 1; i < n_; i++)
    if (types_[i].length) return true;
  return false;
}

bool Model::all_length_deviation() const
{
  for (int i = 1; i < n_; i++)
    if (!types_[i].length) return false;
  return n_ > 1;
}

bool Model::any_contact() const
{
  for (const Pair &p : pairs_)
    if (p.contact) return true;
  return false;
}

double Model::bond_weight(double r, int itype, int jtype, double vi, double vj, double ti,
                          double tj) const
{
  return PeriSISSM::bond_weight(r, horizon(itype, jtype), vi, vj, types_[itype].membrane ? ti : 0.0,
                                types_[jtype].membrane ? tj : 0.0);
}

double Model::stabilization_modulus(int itype, const double Kinv[9]) const
{
  const Type &t = types_[itype];
  return t.membrane ? membrane_stabilization_modulus(t.cs, t.bulk, Kinv)
                    : PeriSISSM::stabilization_modulus(t.cs, t.bulk, Kinv);
}

}    // namespace PeriSISSM
