// Short-range contact (see contact.h).

#include "peri/contact.h"

#include "peri/model.h"

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

double contact_distance(double xi_length, double vi, double vj)
{
  return std::min(0.9 * xi_length, 0.675 * (std::cbrt(vi) + std::cbrt(vj)));
}

double contact_energy(double r, double d, double kc, double vi, double vj)
{
  if (r >= d) return 0.0;
  return 0.5 * kc * vi * vj * (d - r) * (d - r);
}

// f_i = kc V_j (d/r - 1) del:  df_i/dx_i = kc V_j ((d/r - 1) I - (d/r) n n^T).
void contact_block(const double del[3], double kc, double vj, double block[6])
{
  const double r2 = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
  const double b = kc * vj / r2;
  block[0] = b * del[0] * del[0];
  block[1] = b * del[1] * del[1];
  block[2] = b * del[2] * del[2];
  block[3] = b * del[0] * del[1];
  block[4] = b * del[0] * del[2];
  block[5] = b * del[1] * del[2];
}

void contact_pass(const Model &model, const Particles &p, const ReferenceBox &box, double reach,
                  const ContactCandidates &cand, bool newton, bool tally, ContactPairs &pairs,
                  double *block)
{
  const double *x = p.x;
  const double *x0 = p.x0;
  double *f = p.f;
  const double *vfrac = p.volume;
  const int *type = p.type;
  const int nlocal = p.nlocal;
  const bool periodic = box.any();
  const double rmaxsq = reach * reach;

  for (int ii = 0; ii < cand.inum; ii++) {
    const int i = cand.ilist[ii];
    const double xtmp = x[3 * i], ytmp = x[3 * i + 1], ztmp = x[3 * i + 2];
    const int itype = type[i];
    for (int k = cand.first[ii]; k < cand.first[ii + 1]; k++) {
      const int j = cand.neigh[k];
      const double delx = xtmp - x[3 * j];
      const double dely = ytmp - x[3 * j + 1];
      const double delz = ztmp - x[3 * j + 2];
      const double rsq = delx * delx + dely * dely + delz * delz;
      if (rsq >= rmaxsq) continue;
      const int jtype = type[j];
      if (!model.contact(itype, jtype)) continue;
      double dx0 = x0[3 * i] - x0[3 * j];
      double dy0 = x0[3 * i + 1] - x0[3 * j + 1];
      double dz0 = x0[3 * i + 2] - x0[3 * j + 2];
      if (periodic) box.image(dx0, dy0, dz0);
      const double q2 = dx0 * dx0 + dy0 * dy0 + dz0 * dz0;
      // most candidates are bonds near their reference length: rsq > 0.81 q2 (with a margin far
      // above the rounding of either side) settles r >= 0.9 |xi| without the two square roots
      if (rsq > 0.8100001 * q2) continue;
      const double r = sqrt(rsq);
      const double xi = sqrt(q2);
      if (r >= 0.9 * xi || r <= 0.0) continue;
      const double d = contact_distance(xi, vfrac[i], vfrac[j]);
      if (r >= d) continue;
      if (pairs.bonded(i, j)) continue;
      pairs.acting(i, j);

      const double kc = model.kcontact(itype, jtype) / model.horizon(itype, jtype);
      const double fpi = contact_fpair(r, d, kc, vfrac[j]);
      const double fpj = contact_fpair(r, d, kc, vfrac[i]);
      f[3 * i] += delx * fpi;
      f[3 * i + 1] += dely * fpi;
      f[3 * i + 2] += delz * fpi;
      const bool jforce = newton || j < nlocal;
      if (jforce) {
        f[3 * j] -= delx * fpj;
        f[3 * j + 1] -= dely * fpj;
        f[3 * j + 2] -= delz * fpj;
      }
      if (block) {
        const double del[3] = {delx, dely, delz};
        double b[6];
        contact_block(del, kc, vfrac[j], b);
        for (int m = 0; m < 6; m++) block[6 * i + m] += b[m];
        if (jforce) {
          contact_block(del, kc, vfrac[i], b);
          for (int m = 0; m < 6; m++) block[6 * j + m] += b[m];
        }
      }
      if (tally) {
        const double energy =
            2.0 * contact_energy(r, d, kc, vfrac[i], vfrac[j]) / (vfrac[i] + vfrac[j]);
        pairs.tally(i, j, energy, fpi * vfrac[i], delx, dely, delz);
      }
    }
  }
}

}    // namespace PeriSISSM
