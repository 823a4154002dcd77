// The bond-projected stiffness (see bond_stiffness.h).

#include "peri/bond_stiffness.h"

#include "peri/stabilization.h"

#include <cmath>

namespace PeriSISSM {

namespace {

  // S_ij of bond (i, j) of weight omega (bond_stiffness.h), appended to s as xx yy zz xy xz yz
  void stabilization_block(const ParticleFields &fields, const Particles &p, int i, int j,
                           double omega, std::vector<double> &s)
  {
    constexpr int NK = ParticleFields::NK;
    const double *ni = fields.normal + 3 * i, *nj = fields.normal + 3 * j;
    const bool hi = has_normal(ni), hj = has_normal(nj);
    double v[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    if (hi || hj) {
      const double *na = hi ? ni : nj, *nb = hj ? nj : ni;
      const double cs = p.volume[i] * omega * 0.5 *
          (fields.k[NK * i + ParticleFields::K_C] + fields.k[NK * j + ParticleFields::K_C]);
      const int ra[6] = {0, 1, 2, 0, 0, 1}, rb[6] = {0, 1, 2, 1, 2, 2};
      for (int q = 0; q < 6; q++) {
        const int a = ra[q], b = rb[q];
        v[q] = cs * ((a == b ? 1.0 : 0.0) - 0.5 * (na[a] * na[b] + nb[a] * nb[b]));
      }
    }
    s.insert(s.end(), v, v + 6);
  }

}    // namespace

void bond_springs(const Families &fam, const Particles &p, const ParticleFields &fields,
                  bool values, BondSprings &springs)
{
  constexpr int NK = ParticleFields::NK;
  const int nlocal = p.nlocal;
  springs.first.assign(nlocal + 1, 0);
  springs.partner.clear();
  springs.k.clear();
  springs.e.clear();
  springs.s.clear();
  for (int i = 0; i < nlocal; i++) {
    const double *xi = p.x + 3 * i;
    const double *ki = values ? fields.k + NK * i : nullptr;
    const int *jl = fam.jlocal[i];
    const double *om = fam.omega[i];
    for (int b = 0; b < fam.npartner[i]; b++) {
      const int j = jl[b];
      if (j < 0) continue;
      springs.partner.push_back(j);
      if (!values) continue;
      const double *xj = p.x + 3 * j;
      const double *kj = fields.k + NK * j;
      double e[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
      const double len = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      const double inv = len > 0.0 ? 1.0 / len : 0.0;
      for (double &c : e) c *= inv;
      // e^T (H+_i + H+_j) e, H+ stored as xx yy zz xy xz yz
      double h[6];
      for (int c = 0; c < 6; c++) h[c] = ki[c] + kj[c];
      const double ehe = h[0] * e[0] * e[0] + h[1] * e[1] * e[1] + h[2] * e[2] * e[2] +
          2.0 * (h[3] * e[0] * e[1] + h[4] * e[0] * e[2] + h[5] * e[1] * e[2]);
      springs.k.push_back(kBondProjectionFactor * p.volume[i] * om[b] * ehe);
      springs.e.insert(springs.e.end(), e, e + 3);
      if (fields.normal) stabilization_block(fields, p, i, j, om[b], springs.s);
    }
    springs.first[i + 1] = (int) springs.partner.size();
  }
}

}    // namespace PeriSISSM
