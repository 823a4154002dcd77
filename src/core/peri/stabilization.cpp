// Zero-energy-mode stabilization (see stabilization.h).

#include "peri/stabilization.h"

#include "peri/bond_rows.h"

#include <type_traits>

namespace PeriSISSM {

// Cs 18K/(pi delta^5) * kappa_i / kappa_0 with kappa = tr(K^-1)/3 and kappa_0 = 15/(4 pi delta^5):
// the delta^5 and pi cancel, 18 * 4 / 15 / 3 = 8/5.
double stabilization_modulus(double Cs, double K, const double Kinv[9])
{
  return 1.6 * Cs * K * (Kinv[0] + Kinv[4] + Kinv[8]);
}

namespace {

// For each bond
//   z = eta - Fbar xi,  Fbar = a_i F_i + a_j F_j  (a = 1/2 each; 1 and 0 when one end has a
//   singular K and no F),
// direct force density Cbar omega z on i, energy density 1/4 Cbar omega |z|^2 on i, and
// Q_i = -sum_j a_i Cbar omega z (x) xi, so that H_i = A_i + Q_i K_i^-1.
// The loop over the bonds of each particle forms z and the direct force, and stores u = 2 a_i
// Cbar omega z with xi; the 3x3 sum Q of u (x) xi follows from those rows (bond_rows.h). The
// energy is summed only when asked for (EFLAG), which keeps the loop at three accumulators.
template <int EFLAG, int EVFLAG, int PBC>
void pass(const Particles &p, const Families &fam, const ReferenceBox &box,
          ParticleFields &fields, const Virial &virial)
{
  constexpr int NG = ParticleFields::NG;
  const double *xf = p.x;
  const double *rf = p.x0;
  double *f = p.f;
  const double *vfrac = p.volume;
  const int nlocal = p.nlocal;
  const double *gf = fields.g;
  BondRows rows(fam, nlocal);

  for (int i = 0; i < nlocal; i++) {
    const double *gi = gf + NG * i;
    const double *Fi = gi;
    const double ci = gi[ParticleFields::G_C];
    const int regi = gi[ParticleFields::G_REG] > 0.0;
    const double xi0 = xf[3 * i], xi1 = xf[3 * i + 1], xi2 = xf[3 * i + 2];
    const double ri0 = rf[3 * i], ri1 = rf[3 * i + 1], ri2 = rf[3 * i + 2];
    const int n = fam.npartner[i];
    const int *jl = fam.jlocal[i];
    const double *om = fam.omega[i];
    double fx = 0.0, fy = 0.0, fz = 0.0, ws = 0.0;
    BondVirial vir;
    rows.clear();

    for (int b = 0; b < n; b++) {
      const int j = jl[b];
      if (j < 0) continue;
      const double *gj = gf + NG * j;
      const int regj = gj[ParticleFields::G_REG] > 0.0;
      const double *xj = xf + 3 * j;
      const double *rj = rf + 3 * j;
      const double e0 = xj[0] - xi0, e1 = xj[1] - xi1, e2 = xj[2] - xi2;
      double x0 = rj[0] - ri0, x1 = rj[1] - ri1, x2 = rj[2] - ri2;
      if (PBC) box.image(x0, x1, x2);
      double z0, z1, z2, qa;    // qa = 2 a_i (weight of this bond in Q_i, times 2)
      if (regi && regj) {
        // Fbar = (F_i + F_j) / 2
        z0 = e0 - 0.5 * ((Fi[0] + gj[0]) * x0 + (Fi[1] + gj[1]) * x1 + (Fi[2] + gj[2]) * x2);
        z1 = e1 - 0.5 * ((Fi[3] + gj[3]) * x0 + (Fi[4] + gj[4]) * x1 + (Fi[5] + gj[5]) * x2);
        z2 = e2 - 0.5 * ((Fi[6] + gj[6]) * x0 + (Fi[7] + gj[7]) * x1 + (Fi[8] + gj[8]) * x2);
        qa = 1.0;
      } else if (regi || regj) {
        // one end without F: Fbar is the other end's F
        const double *Fo = regi ? Fi : gj;
        z0 = e0 - (Fo[0] * x0 + Fo[1] * x1 + Fo[2] * x2);
        z1 = e1 - (Fo[3] * x0 + Fo[4] * x1 + Fo[5] * x2);
        z2 = e2 - (Fo[6] * x0 + Fo[7] * x1 + Fo[8] * x2);
        qa = regi ? 2.0 : 0.0;
      } else {
        continue;
      }
      const double cw = 0.5 * (ci + gj[ParticleFields::G_C]) * om[b];
      const double t0 = cw * z0, t1 = cw * z1, t2 = cw * z2;
      fx += t0;
      fy += t1;
      fz += t2;
      if (EFLAG) ws += t0 * z0 + t1 * z1 + t2 * z2;
      rows.push(qa * t0, qa * t1, qa * t2, x0, x1, x2);
      if (EVFLAG) vir.add(e0, e1, e2, t0, t1, t2);
    }

    f[3 * i] += fx;
    f[3 * i + 1] += fy;
    f[3 * i + 2] += fz;
    if (EFLAG) fields.w[i] += 0.25 * ws;
    if (EVFLAG) vir.tally(virial, i, -0.5 * vfrac[i]);
    if (!regi) continue;

    double q[9];
    rows.outer_sum(q);
    // H_i = A_i + Q_i K_i^-1 with Q_i = -(sum above)/2 (the sum carries 2 a_i)
    const double *k = fam.kinv[i];
    double *h = fields.h + 9 * i;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        h[3 * r + c] -=
            0.5 * (q[3 * r] * k[c] + q[3 * r + 1] * k[3 + c] + q[3 * r + 2] * k[6 + c]);
  }
}

}  // namespace

void stabilization_pass(const Particles &p, const Families &fam, const ReferenceBox &box,
                        ParticleFields &fields, const Virial &virial, bool energy)
{
  auto run = [&](auto eflag) {
    constexpr int E = decltype(eflag)::value;
    const bool pbc = box.any(), ev = virial.any();
    if (pbc)
      ev ? pass<E, 1, 1>(p, fam, box, fields, virial) : pass<E, 0, 1>(p, fam, box, fields, virial);
    else
      ev ? pass<E, 1, 0>(p, fam, box, fields, virial) : pass<E, 0, 0>(p, fam, box, fields, virial);
  };
  if (energy) run(std::integral_constant<int, 1>());
  else run(std::integral_constant<int, 0>());
}

}  // namespace PeriSISSM
