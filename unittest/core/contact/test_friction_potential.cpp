// Tests of lagged friction over candidate pairs (contact/friction_potential.h) on two facing
// sheets and particles: the lagged pairs are the active candidates with lambda > 0; the forces
// V_i f_i are minus the gradient of the pairs' friction energy in x (central differences); the
// slip from velocities is v dt; the tally counts the pairs and their work; the blocks are the
// diagonal blocks of the pairs' Hessians; the default slip speed in LAMMPS's unit systems.

#include "contact/friction_potential.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::rows_of;
using PeriSISSMContactTest::Scene;

namespace {

Scene scene()
{
  return PeriSISSMContactTest::facing_sheets(0.2, 0.1, 1.55, 0.5 + 1.5 * std::sqrt(2.0), 6);
}

}    // namespace

TEST(FrictionPotential, ForcesAreMinusTheGradientOfTheLaggedEnergy)
{
  Scene s = scene();
  std::vector<Candidate> cands;
  find_candidates(s.atoms(), s.list(), 0.5, cands);
  for (Candidate &c : cands) {
    for (int k = 0; k < c.nv(); k++) c.own[k] = c.v[k];
    c.counts = true;
  }
  const BarrierParameters prm{2.0, 0.15, 0.02};
  std::vector<LaggedPair> lagged;
  build_lagged_pairs(cands, s.rows.data(), prm, lagged);
  int active = 0;
  for (const Candidate &c : cands) {
    Vector3d y[4];
    c.gather(s.rows.data(), y);
    active += c.stencil().distance2(y) < 0.17 * 0.17 &&
        c.stencil().friction_pair(y, c.eps, prm).lambda > 0.0;
  }
  EXPECT_EQ((int) lagged.size(), active);
  ASSERT_GT(active, 5);

  // a tangential move of the second sheet, some of it below the slip length
  std::vector<std::array<double, 3>> x = s.pos;
  std::mt19937_64 rng(8);
  std::normal_distribution<double> n01;
  for (int i = 16; i < (int) x.size(); i++) {
    x[i][0] += 0.01 + 0.003 * n01(rng);
    x[i][1] += 0.003 * n01(rng);
  }
  auto rx = rows_of(x);
  const FrictionParameters fprm{0.4, 0.02};
  std::vector<double> volume(x.size());
  for (std::size_t i = 0; i < x.size(); i++) volume[i] = 0.7 + 0.02 * i;
  std::vector<std::array<double, 3>> force(x.size(), {0.0, 0.0, 0.0});
  auto rf = rows_of(force);
  const FrictionTally t =
      friction_forces(lagged, rx.data(), nullptr, 0.0, fprm, volume.data(), rf.data());
  EXPECT_EQ(t.npairs, (long) lagged.size());
  double work = 0.0;
  for (const LaggedPair &p : lagged) {
    const Vector12d u = lagged_slip(p, rx.data(), nullptr, 0.0);
    const double y = tangential_displacement(p.pair, u).norm();
    work += fprm.mu * p.pair.lambda * friction_f1(y, fprm.slip_length) * y;
  }
  EXPECT_GT(work, 0.0);
  EXPECT_NEAR(t.work, work, 1e-13 * work);

  auto energy = [&]() {
    double D = 0.0;
    for (const LaggedPair &p : lagged)
      D += friction_energy(p.pair, lagged_slip(p, rx.data(), nullptr, 0.0), fprm);
    return D;
  };
  const double h = 1e-7;
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < x.size(); i++)
    for (int d = 0; d < 3; d++) {
      const double x0 = x[i][d];
      x[i][d] = x0 + h;
      const double Ep = energy();
      x[i][d] = x0 - h;
      const double Em = energy();
      x[i][d] = x0;
      const double g = (Ep - Em) / (2.0 * h);
      worst = std::max(worst, std::fabs(force[i][d] * volume[i] + g));
      scale = std::max(scale, std::fabs(g));
    }
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(worst, 1e-6 * scale);

  // the slip from velocities: v dt
  std::vector<std::array<double, 3>> v(x.size());
  for (std::size_t i = 0; i < x.size(); i++)
    for (int d = 0; d < 3; d++) v[i][d] = (x[i][d] - s.pos[i][d]) / 0.5;
  auto rv = rows_of(v);
  for (const LaggedPair &p : lagged) {
    const Vector12d a = lagged_slip(p, rx.data(), nullptr, 0.0);
    const Vector12d b = lagged_slip(p, nullptr, rv.data(), 0.5);
    EXPECT_LE((a - b).norm(), 1e-14);
  }

  // blocks: the diagonal blocks of each pair's Hessian / V
  std::vector<std::array<double, 6>> blk(x.size(), {0, 0, 0, 0, 0, 0});
  std::vector<double *> rb;
  for (auto &q : blk) rb.push_back(q.data());
  friction_blocks(lagged, rx.data(), fprm, volume.data(), rb.data());
  std::vector<std::array<double, 6>> ref(x.size(), {0, 0, 0, 0, 0, 0});
  for (const LaggedPair &p : lagged) {
    const Matrix12d H = friction_hessian(p.pair, lagged_slip(p, rx.data(), nullptr, 0.0), fprm);
    for (int k = 0; k < p.pair.count; k++) {
      const int o = 3 * k, i = p.v[k];
      const double e[6] = {H(o, o),     H(o + 1, o + 1), H(o + 2, o + 2),
                           H(o, o + 1), H(o, o + 2),     H(o + 1, o + 2)};
      for (int m = 0; m < 6; m++) ref[i][m] += e[m] / volume[i];
    }
  }
  for (std::size_t i = 0; i < x.size(); i++)
    for (int m = 0; m < 6; m++)
      EXPECT_NEAR(blk[i][m], ref[i][m], 1e-12 * std::fabs(ref[i][m]) + 1e-300);
}

// IPC's 1e-3 m/s in LAMMPS's unit systems (force->angstrom and force->femtosecond of each)
TEST(FrictionPotential, DefaultSlipSpeed)
{
  EXPECT_DOUBLE_EQ(default_slip_speed(1.0e-10, 1.0e-15), 1.0e-3);    // si: m/s
  EXPECT_DOUBLE_EQ(default_slip_speed(1.0e-8, 1.0e-15), 0.1);        // cgs: cm/s
  EXPECT_DOUBLE_EQ(default_slip_speed(1.0, 1.0e-3), 1.0e-5);         // metal: A/ps
  EXPECT_DOUBLE_EQ(default_slip_speed(1.0, 1.0), 1.0e-8);            // real: A/fs
  EXPECT_DOUBLE_EQ(default_slip_speed(1.0e-4, 1.0e-9), 1.0e-3);      // micro: um/us
}
