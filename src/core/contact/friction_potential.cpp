#include "contact/friction_potential.h"

#include "contact/barrier_potential.h"

using Eigen::Vector3d;

namespace PeriSISSM {

double default_slip_speed(double angstrom, double femtosecond)
{
  return 1.0e-3 * 1.0e10 * angstrom / (1.0e15 * femtosecond);
}

void build_lagged_pairs(const std::vector<Candidate> &candidates, const double *const *x,
                        const BarrierParameters &prm, std::vector<LaggedPair> &lagged)
{
  const double range = prm.dmin + prm.dhat;
  lagged.clear();
  for (const Candidate &c : candidates) {
    const int nv = c.nv();
    Vector3d y[4];
    c.gather(x, y);
    const double D = c.stencil().distance2(y);
    // (a pair at or within dmin is an error of the force evaluation)
    if (!(D < range * range) || !(D > prm.dmin * prm.dmin)) continue;
    LaggedPair l;
    for (int k = 0; k < 4; k++) {
      l.v[k] = c.v[k];
      l.own[k] = c.own[k];
      for (int d = 0; d < 3; d++) l.xn[3 * k + d] = k < nv ? y[k][d] : 0.0;
    }
    l.counts = c.counts;
    l.pair = c.stencil().friction_pair(y, c.eps, prm);
    if (l.pair.lambda > 0.0) lagged.push_back(l);
  }
}

Vector12d lagged_slip(const LaggedPair &p, const double *const *x, const double *const *vel,
                      double dt)
{
  Vector12d u = Vector12d::Zero();
  for (int k = 0; k < p.pair.count; k++)
    for (int d = 0; d < 3; d++)
      u[3 * k + d] = vel ? vel[p.v[k]][d] * dt : x[p.v[k]][d] - p.xn[3 * k + d];
  return u;
}

FrictionTally friction_forces(const std::vector<LaggedPair> &lagged, const double *const *x,
                              const double *const *vel, double dt, const FrictionParameters &prm,
                              const double *volume, double **f)
{
  FrictionTally t;
  for (const LaggedPair &p : lagged) {
    const Vector12d u = lagged_slip(p, x, vel, dt);
    if (p.counts) {
      const double y = tangential_displacement(p.pair, u).norm();
      t.npairs++;
      t.work += prm.mu * p.pair.lambda * friction_f1(y, prm.slip_length) * y;
    }
    const Vector12d g = friction_gradient(p.pair, u, prm);
    for (int k = 0; k < p.pair.count; k++) {
      const int i = p.own[k];
      if (i < 0) continue;
      for (int d = 0; d < 3; d++) f[i][d] -= g[3 * k + d] / volume[i];
    }
  }
  return t;
}

void friction_blocks(const std::vector<LaggedPair> &lagged, const double *const *x,
                     const FrictionParameters &prm, const double *volume, double **block)
{
  for (const LaggedPair &p : lagged)
    add_diagonal_blocks(friction_hessian(p.pair, lagged_slip(p, x, nullptr, 0.0), prm),
                        p.pair.count, p.own, volume, block);
}

}    // namespace PeriSISSM
