// Coefficients of type pairs (see coefficients.h).

#include "peri/coefficients.h"

#include "linalg/constants.h"
#include "materials/material.h"
#include "peri/breaking.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

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
  m.length = ii.length && jj.length;
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

void add_spacing_sums(int n, const double *volume, const int *type, std::vector<double> &sums)
{
  for (int k = 0; k < n; k++) {
    const double hk = std::cbrt(volume[k]);
    sums[2 * type[k]] += hk;
    sums[2 * type[k] + 1] += 1.0;
    sums[0] += hk;
    sums[1] += 1.0;
  }
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

bool CoefficientTable::any_g0() const
{
  for (int i = 1; i < n_; i++)
    for (int j = i; j < n_; j++)
      if (given(i, j) && at(i, j).g0 > 0.0) return true;
  return false;
}

bool CoefficientTable::any_contact() const
{
  for (int i = 1; i < n_; i++)
    for (int j = i; j < n_; j++)
      if (at(i, j).contact) return true;
  return false;
}

double CoefficientTable::largest_horizon() const
{
  double most = 0.0;
  for (int i = 1; i < n_; i++)
    for (int j = 1; j < n_; j++) most = std::max(most, at(i, j).horizon);
  return most;
}

double CoefficientTable::smallest_contact_horizon() const
{
  double least = DBL_MAX;
  for (int i = 1; i < n_; i++)
    for (int j = i; j < n_; j++)
      if (at(i, j).contact) least = std::min(least, at(i, j).horizon);
  return least;
}

std::vector<double> CoefficientTable::bending_factors(const std::vector<double> &bend) const
{
  std::vector<double> factor(n_, 0.0);
  for (int t = 1; t < n_; t++)
    if (bend[t] != 0.0) factor[t] = bending_factor(at(t, t).moduli);
  return factor;
}

bool CoefficientTable::unbent_membrane(int t, const std::vector<double> &bend) const
{
  return at(t, t).membrane && (t >= (int) bend.size() || bend[t] == 0.0);
}

bool CoefficientTable::set_s00_from_g0(const std::vector<double> &sums, std::string &log,
                                       int &bad_i, int &bad_j)
{
  for (int i = 1; i < n_; i++) {
    for (int j = i; j < n_; j++) {
      PairCoefficients &c = at(i, j);
      if (!given(i, j) || c.g0 <= 0.0) continue;
      double h = 0.0;
      if (!pair_spacing(sums, i, j, h)) {
        bad_i = i;
        bad_j = j;
        return false;
      }
      const double s00 =
          s00_from_fracture_energy(c.g0, c.moduli.k, c.moduli.g, c.cs, c.horizon, h, c.length);
      if (s00 != c.s00) {
        char line[256];
        std::snprintf(line, sizeof(line),
                      "peri/nosb: types %d %d: G0 = %.6g gives s00 = %.6g (K = %.6g, G = %.6g, "
                      "Cs = %.6g%s, horizon = %.6g = %.5g h)\n",
                      i, j, c.g0, s00, c.moduli.k, c.moduli.g, c.cs,
                      c.length ? " deviation length" : "", c.horizon, c.horizon / h);
        log += line;
      }
      c.s00 = s00;
    }
  }
  return true;
}

void CoefficientTable::configure(Model &model) const
{
  const int n = ntypes();
  model.set_ntypes(n);
  for (int i = 1; i <= n; i++) {
    const PairCoefficients &own = at(i, i);
    model.set_type(i, make_material(own.moduli), own.cs, bulk_modulus(own.moduli));
    model.set_membrane(i, own.membrane);
    model.set_length_deviation(i, own.length);
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

namespace {

  template <class T> void append(std::string &bytes, const T *values, int n)
  {
    bytes.append(reinterpret_cast<const char *>(values), sizeof(T) * n);
  }

}    // namespace

std::string coefficients_restart_bytes(const CoefficientTable &table,
                                       const std::vector<double> &bend)
{
  std::string bytes;
  const int n = table.ntypes();
  append(bytes, &kCoefficientsRestartVersion, 1);
  for (int i = 1; i <= n; i++) {
    for (int j = i; j <= n; j++) {
      const int given = table.given(i, j) ? 1 : 0;
      append(bytes, &given, 1);
      if (!given) continue;
      const PairCoefficients &c = table.at(i, j);
      const int len = (int) c.moduli.model.size() + 1;
      append(bytes, &len, 1);
      append(bytes, c.moduli.model.c_str(), len);
      const int flags[5] = {c.breaks ? 1 : 0, c.contact ? 1 : 0, c.membrane ? 1 : 0,
                            c.length ? 1 : 0, c.plate ? 1 : 0};
      const double values[6] = {c.moduli.k, c.moduli.g, c.horizon, c.s00, c.alpha, c.cs};
      append(bytes, flags, 5);
      append(bytes, values, 6);
    }
  }
  std::vector<double> types(bend.begin(), bend.end());
  types.resize(n + 1, 0.0);
  append(bytes, types.data() + 1, n);
  return bytes;
}

std::string read_coefficients_restart(const std::function<void(void *, std::size_t)> &read,
                                      CoefficientTable &table, std::vector<double> &bend)
{
  const int n = table.ntypes();
  int version = 0;
  read(&version, sizeof(int));
  if (version != kCoefficientsRestartVersion)
    return "Pair peri/nosb: the restart file holds pair data of format version " +
        std::to_string(version) + ", this build reads version " +
        std::to_string(kCoefficientsRestartVersion) +
        ": write the restart file again with this build (or use the build that wrote it)";
  for (int i = 1; i <= n; i++) {
    for (int j = i; j <= n; j++) {
      int given = 0, len = 0;
      read(&given, sizeof(int));
      if (!given) continue;
      read(&len, sizeof(int));
      if (len < 1 || len > 256)
        return "Pair peri/nosb: restart file is corrupt (model name of " + std::to_string(len) +
            " chars)";
      std::vector<char> name(len);
      int flags[5];
      double values[6];
      read(name.data(), len);
      read(flags, sizeof(flags));
      read(values, sizeof(values));
      name[len - 1] = '\0';
      const auto &names = material_names();
      if (std::find(names.begin(), names.end(), std::string(name.data())) == names.end())
        return "Pair peri/nosb: restart file names model '" + std::string(name.data()) +
            "', which this build does not have (allowed: " + material_names_joined() + ")";
      PairCoefficients c;
      c.moduli.model = name.data();
      c.breaks = flags[0] != 0;
      c.contact = flags[1] != 0;
      c.membrane = flags[2] != 0;
      c.length = flags[3] != 0;
      c.plate = flags[4] != 0;
      c.moduli.k = values[0];
      c.moduli.g = values[1];
      c.horizon = values[2];
      c.s00 = values[3];
      c.alpha = values[4];
      c.cs = values[5];
      table.set(i, j, c);
    }
  }
  bend.assign(n + 1, 0.0);
  read(bend.data() + 1, sizeof(double) * n);
  return "";
}

}    // namespace PeriSISSM
