// Tests of the barrier over candidate pairs (contact/barrier_potential.h) on two facing sheets
// and particles between them: the forces V_i f_i are minus the gradient of the pairs' energy
// sum (central differences), the energy densities sum to the energy when every vertex is owned,
// only owned vertices get shares, the tally counts, a pair within dmin stops the pass, and the
// diagonal blocks are those of the pairs' projected Hessians.

#include "contact/barrier_potential.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::Scene;

namespace {

Scene scene()
{
  return PeriSISSMContactTest::facing_sheets(0.2, 0.1, 1.55, 0.5 + 1.5 * std::sqrt(2.0), 3);
}

std::vector<Candidate> owned_candidates(const Scene &s, double reach)
{
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), reach, cands);
  for (Candidate &c : cands) {
    for (int k = 0; k < c.nv(); k++) c.own[k] = c.v[k];
    c.counts = true;
  }
  return cands;
}

double energy(const std::vector<Candidate> &cands, const Scene &s, const BarrierParameters &prm)
{
  double E = 0.0;
  for (const Candidate &c : cands) {
    Vector3d y[4];
    c.gather(s.rows.data(), y);
    E += c.stencil().barrier_energy(y, c.eps, prm);
  }
  return E;
}

}    // namespace

TEST(BarrierPotential, ForcesAreMinusTheGradientOfTheEnergy)
{
  Scene s = scene();
  const BarrierParameters prm{2.0, 0.15, 0.02};
  const std::vector<Candidate> cands = owned_candidates(s, 0.5);
  std::vector<double> volume(s.n());
  for (int i = 0; i < s.n(); i++) volume[i] = 0.5 + 0.01 * i;
  std::vector<std::array<double, 3>> force(s.n(), {0.0, 0.0, 0.0});
  std::vector<double *> f;
  for (auto &q : force) f.push_back(q.data());
  CandidateDistances dist;
  dist.evaluate(cands, s.rows.data(), s.n(), 1, prm.dmin + prm.dhat, 1.0, 0.1);
  const BarrierTally t =
      barrier_forces(cands, dist, s.rows.data(), volume.data(), prm, 1.0, f.data());
  EXPECT_EQ(t.too_close, -1);
  EXPECT_EQ(t.ncandidates, (long) cands.size());
  EXPECT_GT(t.nactive[0] + t.nactive[1], 5);
  EXPECT_GT(t.nactive[2], 0);
  const double E = energy(cands, s, prm);
  EXPECT_GT(E, 0.0);
  EXPECT_NEAR(t.energy_pairs, E, 1e-13 * E);
  double mind = 1.0;
  for (std::size_t ic = 0; ic < cands.size(); ic++) mind = std::min(mind, dist[ic]);
  EXPECT_EQ(t.mindist, mind);
  // each vertex of a pair gets E / (n V)
  double density = 0.0;
  for (const Candidate &c : cands) {
    Vector3d y[4];
    c.gather(s.rows.data(), y);
    const double Ec = c.stencil().barrier_energy(y, c.eps, prm);
    for (int k = 0; k < c.nv(); k++) density += Ec / c.nv() / volume[c.v[k]];
  }
  EXPECT_GT(density, 0.0);
  EXPECT_NEAR(t.energy_density, density, 1e-13 * density);
  // central differences of E, step 1e-6 (E smooth there: every gap well above 0)
  const double h = 1e-6;
  double worst = 0.0, scale = 0.0;
  for (int i = 0; i < s.n(); i++)
    for (int d = 0; d < 3; d++) {
      const double x0 = s.pos[i][d];
      s.pos[i][d] = x0 + h;
      const double Ep = energy(cands, s, prm);
      s.pos[i][d] = x0 - h;
      const double Em = energy(cands, s, prm);
      s.pos[i][d] = x0;
      const double g = (Ep - Em) / (2.0 * h);
      worst = std::max(worst, std::fabs(force[i][d] * volume[i] + g));
      scale = std::max(scale, std::fabs(g));
    }
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(worst, 1e-6 * scale);

  // ghost vertices (own -1) get nothing; a pair within dmin stops the pass
  std::vector<Candidate> half = cands;
  for (Candidate &c : half) c.own[0] = -1;
  for (auto &q : force) q = {0.0, 0.0, 0.0};
  barrier_forces(half, dist, s.rows.data(), volume.data(), prm, 1.0, f.data());
  int checked = 0;
  for (const Candidate &c : cands) {
    bool elsewhere = false;
    for (const Candidate &o : cands)
      for (int k = 1; k < o.nv(); k++) elsewhere = elsewhere || o.v[k] == c.v[0];
    if (elsewhere) continue;
    checked++;
    for (int d = 0; d < 3; d++) EXPECT_EQ(force[c.v[0]][d], 0.0);
  }
  EXPECT_GT(checked, 0);
  const BarrierParameters thick{2.0, 0.15, 0.12};
  const BarrierTally stop =
      barrier_forces(cands, dist, s.rows.data(), volume.data(), thick, 1.0, f.data());
  ASSERT_GE(stop.too_close, 0);
  EXPECT_LE(dist[stop.too_close], thick.dmin);
}

// The error of a pair within dmin names its kind, its IDs in canonical order and both numbers
TEST(BarrierPotential, TooCloseErrorNamesThePair)
{
  Candidate pt{StencilType::kPointTriangle, {7, 2, 3, 11}, {0, 1, 2, 3}};
  EXPECT_EQ(too_close_error(pt, 0.000123456789, 0.0005),
            "the " + std::string(pt.stencil().name()) +
                " pair of atoms 7 2 3 11 is 0.000123457 apart, not more than dmin = 0.0005: the "
                "barrier is infinite there (the primitives came through the barrier: use a larger "
                "kappa, a smaller time step or a larger dhat)");
  Candidate pp{StencilType::kPointPoint, {4, 9, 0, 0}, {0, 1, -1, -1}};
  const std::string e = too_close_error(pp, 0.0, 1e-7);
  EXPECT_NE(e.find(" pair of atoms 4 9 is 0 apart, not more than dmin = 1e-07:"), std::string::npos)
      << e;
  EXPECT_NE(e.find(pp.stencil().name()), std::string::npos);
}

TEST(BarrierPotential, BlocksAreTheProjectedHessiansDiagonalBlocks)
{
  Scene s = scene();
  const BarrierParameters prm{2.0, 0.15, 0.02};
  const std::vector<Candidate> cands = owned_candidates(s, 0.5);
  std::vector<double> volume(s.n(), 2.0);
  std::vector<std::array<double, 6>> blk(s.n(), {0, 0, 0, 0, 0, 0});
  std::vector<double *> b;
  for (auto &q : blk) b.push_back(q.data());
  CandidateDistances dist;
  dist.evaluate(cands, s.rows.data(), s.n(), 1, prm.dmin + prm.dhat, 1.0, 0.1);
  // the pairs within the range, as the forces found them
  std::vector<std::array<double, 3>> force(s.n(), {0.0, 0.0, 0.0});
  auto f = PeriSISSMContactTest::rows_of(force);
  std::vector<int> active;
  barrier_forces(cands, dist, s.rows.data(), volume.data(), prm, 1.0, f.data(), &active);
  std::vector<int> within;
  for (std::size_t ic = 0; ic < cands.size(); ic++)
    if (dist[ic] < prm.dmin + prm.dhat) within.push_back((int) ic);
  EXPECT_EQ(active, within);
  barrier_blocks(cands, active, s.rows.data(), volume.data(), prm, b.data());
  std::vector<std::array<double, 6>> ref(s.n(), {0, 0, 0, 0, 0, 0});
  for (std::size_t ic = 0; ic < cands.size(); ic++) {
    const Candidate &c = cands[ic];
    if (!(dist[ic] < prm.dmin + prm.dhat)) continue;
    Vector3d y[4];
    c.gather(s.rows.data(), y);
    const Matrix12d H = c.stencil().barrier_hessian(y, c.eps, prm, true);
    for (int k = 0; k < c.nv(); k++) {
      const int o = 3 * k, i = c.v[k];
      const double e[6] = {H(o, o),     H(o + 1, o + 1), H(o + 2, o + 2),
                           H(o, o + 1), H(o, o + 2),     H(o + 1, o + 2)};
      for (int m = 0; m < 6; m++) ref[i][m] += e[m] / 2.0;
    }
  }
  int nonzero = 0;
  for (int i = 0; i < s.n(); i++) {
    for (int m = 0; m < 6; m++) EXPECT_NEAR(blk[i][m], ref[i][m], 1e-12 * std::fabs(ref[i][m]));
    EXPECT_GE(blk[i][0], 0.0);    // PSD: non-negative diagonal
    nonzero += blk[i][0] > 0.0;
  }
  EXPECT_GT(nonzero, 5);
}
