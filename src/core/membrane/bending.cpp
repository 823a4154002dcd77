// The bending term of membranes over a distributed triangle mesh (see bending.h).

#include "membrane/bending.h"

#include "membrane/hinge.h"
#include "peri/bond_stiffness.h"
#include "peri/stable_step.h"

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

std::int64_t build_hinges(const HingeMesh &mesh, const double *x0, const ReferenceBox &box,
                          std::vector<Hinge> &hinges, bool plate_edges)
{
  const int nlocal = mesh.nlocal();
  std::int64_t missing = 0;
  hinges.clear();

  // the hinge (w[0], w[1] | w[2], w[3]) found by owned row i; false if a vertex is not here
  auto add = [&](int i, const int w[4]) {
    for (int k = 0; k < 4; k++)
      if (w[k] < 0) return false;
    // the edge from its smaller ID, the same hinge as (w[1], w[0] | w[3], w[2])
    const bool flip = mesh.id(w[0]) > mesh.id(w[1]);
    const int v[4] = {w[flip], w[!flip], w[2 + flip], w[2 + !flip]};
    Hinge h;
    for (int k = 0; k < 4; k++) {
      h.v[k] = v[k];
      // the owned row itself, also where its closest image to i is a periodic ghost
      h.own[k] = mesh.sharer(mesh.id(v[k]));
      if (h.own[k] >= 0 && h.own[k] < i) return true;    // listed by that smaller vertex
    }
    if ((mesh.plate(v[0]) && mesh.plate(v[1])) != plate_edges) return true;
    const double D = 0.5 * (mesh.modulus(v[0]) + mesh.modulus(v[1]));
    if (D <= 0.0) return true;
    // reference positions relative to x0 (minimum image in the reference box)
    double X[4][3];
    for (int k = 0; k < 4; k++) {
      for (int d = 0; d < 3; d++) X[k][d] = x0[3 * v[k] + d] - x0[3 * v[0] + d];
      if (box.any()) box.image(X[k][0], X[k][1], X[k][2]);
    }
    h.c = hinge_stiffness(D, X[0], X[1], X[2], X[3]);
    h.theta0 = hinge_angle(X[0], X[1], X[2], X[3]);
    hinges.push_back(h);
    return true;
  };

  for (int i = 0; i < nlocal; i++) {
    if (mesh.sharer(mesh.id(i)) != i) continue;
    const int ntri = mesh.ntri(i);
    for (int k = 0; k < ntri; k++) {
      std::int64_t a, b;
      mesh.triangle(i, k, a, b);
      // the edge (i, a): triangles (i, a, b) and (a, i, c) = i's (i, c, a)
      for (int k2 = 0; k2 < ntri; k2++) {
        std::int64_t c, a2;
        mesh.triangle(i, k2, c, a2);
        if (a2 != a) continue;
        const int v[4] = {i, mesh.image(i, a), mesh.image(i, b), mesh.image(i, c)};
        if (!add(i, v)) missing = mesh.id(i);
        break;
      }
      // the edge (a, b) opposite i: triangles (a, b, i) and (b, a, d) = a's (a, d, b)
      const int ja = mesh.image(i, a);
      if (ja < 0) {
        missing = mesh.id(i);
        continue;
      }
      const int ntria = mesh.ntri(ja);
      for (int k2 = 0; k2 < ntria; k2++) {
        std::int64_t d, b2;
        mesh.triangle(ja, k2, d, b2);
        if (b2 != b) continue;
        const int v[4] = {ja, mesh.image(i, b), i, mesh.image(i, d)};
        if (!add(i, v)) missing = mesh.id(i);
        break;
      }
    }
  }
  // in the order of their edges' IDs (see bending.h): a run continued from a restart file,
  // whose particles are sorted anew, gets the same bending forces to the last bit
  std::sort(hinges.begin(), hinges.end(), [&mesh](const Hinge &p, const Hinge &q) {
    const std::int64_t p0 = mesh.id(p.v[0]), q0 = mesh.id(q.v[0]);
    return p0 != q0 ? p0 < q0 : mesh.id(p.v[1]) < mesh.id(q.v[1]);
  });
  return missing;
}

void tally_virial(const Virial &virial, int i, const double *xv, const double *xref,
                  const double *F)
{
  const double r[3] = {xv[0] - xref[0], xv[1] - xref[1], xv[2] - xref[2]};
  const double w[6] = {r[0] * F[0], r[1] * F[1], r[2] * F[2],
                       r[0] * F[1], r[0] * F[2], r[1] * F[2]};
  if (virial.global)
    for (int m = 0; m < 6; m++) virial.global[m] += w[m];
  if (virial.peratom)
    for (int m = 0; m < 6; m++) virial.peratom[i][m] += w[m];
}

void bending_pass(const std::vector<Hinge> &hinges, const Particles &p, double **block,
                  const BendingEnergy &energy, const Virial &virial)
{
  const double *x = p.x;
  double *f = p.f;
  const double *vfrac = p.volume;
  const bool tally_energy = energy.total || energy.per_particle;

  for (const Hinge &h : hinges) {
    const int *v = h.v;
    double force[4][3], blk[4][6];
    const double E = hinge_energy(x + 3 * v[0], x + 3 * v[1], x + 3 * v[2], x + 3 * v[3], h.theta0,
                                  h.c, force, block ? blk : nullptr);
    for (int k = 0; k < 4; k++) {
      const int i = h.own[k];
      if (i < 0) continue;
      const double vi = vfrac[i];
      for (int d = 0; d < 3; d++) f[3 * i + d] += force[k][d] / vi;
      if (block)
        for (int m = 0; m < 6; m++) block[i][m] += blk[k][m] / vi;
      if (tally_energy) {
        const double e = 0.25 * E / vi;
        if (energy.total) *energy.total += e;
        if (energy.per_particle) energy.per_particle[i] += e;
      }
      if (virial.any()) tally_virial(virial, i, x + 3 * v[k], x + 3 * v[0], force[k]);
    }
  }
}

void bending_stable_steps(const std::vector<Hinge> &hinges, const Particles &p, const double *rho,
                          double *dt, double *stiffness)
{
  const double *x = p.x;
  std::vector<double> G(p.nlocal, 0.0);
  for (const Hinge &h : hinges) {
    const int *v = h.v;
    double g[4][3], norm[4], sum = 0.0;
    hinge_angle(x + 3 * v[0], x + 3 * v[1], x + 3 * v[2], x + 3 * v[3], g);
    for (int k = 0; k < 4; k++) {
      norm[k] = std::sqrt(g[k][0] * g[k][0] + g[k][1] * g[k][1] + g[k][2] * g[k][2]);
      sum += norm[k];
    }
    for (int k = 0; k < 4; k++)
      if (h.own[k] >= 0) G[h.own[k]] += 2.0 * h.c * norm[k] * sum / p.volume[h.own[k]];
  }
  combine_stable_steps(G, rho, dt, stiffness);
}

void combine_stable_steps(const std::vector<double> &G, const double *rho, double *dt,
                          double *stiffness)
{
  for (int i = 0; i < (int) G.size(); i++) {
    if (!(G[i] > 0.0)) continue;
    if (stiffness) stiffness[i] += G[i];
    const double dtb = stable_time_step(rho[i], G[i]);
    dt[i] = std::isinf(dt[i]) ? dtb : 1.0 / std::sqrt(1.0 / (dt[i] * dt[i]) + 1.0 / (dtb * dtb));
  }
}

void hinge_couplings(const std::vector<Hinge> &hinges, const Particles &p, bool gradients,
                     HingeCouplings &couplings)
{
  couplings.vertex.clear();
  couplings.row.clear();
  couplings.grad.clear();
  const double *x = p.x;
  for (const Hinge &h : hinges) {
    const int *v = h.v;
    for (int k = 0; k < 4; k++) {
      couplings.vertex.push_back(v[k]);
      couplings.row.push_back(h.own[k]);
    }
    if (!gradients) continue;
    double g[4][3];
    hinge_angle(x + 3 * v[0], x + 3 * v[1], x + 3 * v[2], x + 3 * v[3], g);
    const double s = std::sqrt(2.0 * h.c);
    for (int k = 0; k < 4; k++)
      for (int d = 0; d < 3; d++) couplings.grad.push_back(s * g[k][d]);
  }
}

}    // namespace PeriSISSM
