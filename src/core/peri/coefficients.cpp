// Coefficients of type pairs (see coefficients.h).

#include "peri/coefficients.h"

#include "linalg/constants.h"

#include <algorithm>

namespace PeriSISSM {

PairCoefficients mix_coefficients(const PairCoefficients &ii, const PairCoefficients &jj)
{
  // the critical stretch comes from the weaker of the types whose bonds can break (a 'break
  // no' type has no meaningful s00)
  const PairCoefficients *weak = (ii.s00 <= jj.s00) ? &ii : &jj;
  if (ii.breaks != jj.breaks) weak = ii.breaks ? &ii : &jj;
  PairCoefficients m;
  m.moduli.model = ii.moduli.model;
  m.moduli.k = 0.5 * (ii.moduli.k + jj.moduli.k);
  m.moduli.g = 0.5 * (ii.moduli.g + jj.moduli.g);
  m.horizon = std::max(ii.horizon, jj.horizon);
  m.s00 = weak->s00;
  m.alpha = weak->alpha;
  m.cs = 0.0;
  m.g0 = 0.0;
  m.breaks = ii.breaks || jj.breaks;
  m.contact = ii.contact || jj.contact;
  m.membrane = false;
  return m;
}

double contact_stiffness(double bulk, double horizon)
{
  const double d2 = horizon * horizon;
  return 15.0 * 18.0 * bulk / (kPi * d2 * d2);
}

bool pair_spacing(const std::vector<double> &sums, int i, int j, double &h)
{
  double hsum = sums[2 * i] + (j != i ? sums[2 * j] : 0.0);
  double count = sums[2 * i + 1] + (j != i ? sums[2 * j + 1] : 0.0);
  if (count == 0.0) {
    hsum = sums[0];
    count = sums[1];
  }
  if (count == 0.0) return false;
  h = hsum / count;
  return true;
}

void CoefficientTable::resize(int ntypes)
{
  n_ = ntypes + 1;
  c_.assign(n_ * n_, PairCoefficients());
  given_.assign(n_ * n_, 0);
}

void CoefficientTable::set(int i, int j, const PairCoefficients &c)
{
  c_[i * n_ + j] = c;
  given_[i * n_ + j] = 1;
}

void CoefficientTable::complete()
{
  for (int i = 1; i < n_; i++)
    for (int j = i + 1; j < n_; j++)
      if (!given(i, j)) at(i, j) = mix_coefficients(at(i, i), at(j, j));
  for (int i = 1; i < n_; i++)
    for (int j = i + 1; j < n_; j++) at(j, i) = at(i, j);
}

bool CoefficientTable::any_break() const
{
  for (int i = 1; i < n_; i++)
    for (int j = i; j < n_; j++)
      if (at(i, j).breaks) return true;
  return false;
}

bool CoefficientTable::any_contact() const
{
  for (int i = 1; i < n_; i++)
    for (int j = i; j < n_; j++)
      if (at(i, j).contact) return true;
  return false;
}

void CoefficientTable::configure(Model &model) const
{
  const int n = ntypes();
  model.set_ntypes(n);
  for (int i = 1; i <= n; i++) {
    const PairCoefficients &own = at(i, i);
    model.set_type(i, make_material(own.moduli), own.cs, bulk_modulus(own.moduli));
    model.set_membrane(i, own.membrane);
    for (int j = i; j <= n; j++) {
      const PairCoefficients &c = at(i, j);
      model.set_pair(i, j, c.horizon, c.contact, contact_stiffness(c.moduli.k, c.horizon));
    }
  }
  model.breaking().configure(
      n,
      [this](int i, int j) {
        return at(i, j).breaks;
      },
      [this](int i, int j) {
        return at(i, j).s00;
      },
      [this](int i, int j) {
        return at(i, j).alpha;
      });
}

}    // namespace PeriSISSM
