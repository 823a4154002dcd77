// Tests of the short-range contact pass (peri/contact.h) over a small squeezed cluster without
// LAMMPS: its forces against finite differences of the energy it reports, its blocks against
// the stiffness of its forces, the pairs it leaves alone (bonded, beyond the contact distance,
// types without contact), and the rows that get a pair's force and block with and without
// newton.

#include "materials/material.h"
#include "peri/contact.h"
#include "peri/model.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

using PeriSISSMTest::central_difference;
using PeriSISSMTest::central_differences;
using PeriSISSMTest::unit_direction;

namespace {

constexpr int N = 8;

// two types with contact between each other and within type 1, none within type 2
PeriSISSM::Model make_model()
{
  PeriSISSM::Model m;
  m.set_ntypes(2);
  const auto lame = PeriSISSM::lame_from_bulk_shear(1.0, 0.6);
  for (int t = 1; t <= 2; t++)
    m.set_type(t, PeriSISSM::make_material("linear", lame.mu, lame.lambda), 0.0, 1.0);
  m.set_pair(1, 1, 2.0, true, 5.0);
  m.set_pair(1, 2, 2.5, true, 7.0);
  m.set_pair(2, 2, 2.0, false, 5.0);
  return m;
}

// the pairs of the cluster: one pair bonded, the others not
class Pairs : public PeriSISSM::ContactPairs {
 public:
  explicit Pairs(const std::vector<double> &volume) : volume_(volume) {}
  bool bonded(int i, int j) const override { return (i == 0 && j == 1) || (i == 1 && j == 0); }
  void acting(int i, int j) override { acting_pairs.insert({i, j}); }
  void tally(int i, int j, double energy, double, double, double, double) override
  {
    // energy = 2 E / (V_i + V_j)
    total += 0.5 * energy * (volume_[i] + volume_[j]);
  }
  double total = 0.0;
  std::set<std::pair<int, int>> acting_pairs;

 private:
  const std::vector<double> &volume_;
};

struct Cluster {
  std::vector<double> x0, volume;
  std::vector<int> type;
  std::vector<int> ilist, first, neigh;    // a half list of all pairs

  Cluster() : x0(3 * N), volume(N), type(N)
  {
    for (int i = 0; i < N; i++) {
      // reference positions two units apart: 0.9 |xi| is never the contact distance here
      x0[3 * i] = 2.0 * (i % 4);
      x0[3 * i + 1] = 2.0 * (i / 4);
      x0[3 * i + 2] = 0.3 * i;
      volume[i] = 0.15 + 0.02 * i;
      type[i] = i == 5 || i == 6 ? 2 : 1;
    }
    for (int i = 0; i < N; i++) {
      ilist.push_back(i);
      first.push_back((int) neigh.size());
      for (int j = i + 1; j < N; j++) neigh.push_back(j);
    }
    first.push_back((int) neigh.size());
  }

  // every particle squeezed into a ball of radius ~0.6: most pairs are within contact distance
  // 0.675 (V_i^(1/3) + V_j^(1/3)) ~ 0.7 .. 0.9
  std::vector<double> squeezed(unsigned seed) const
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> x(3 * N);
    for (double &c : x) c = 0.6 * u(rng);
    return x;
  }

  struct Result {
    std::vector<double> f, block;
    double energy = 0.0;
    std::set<std::pair<int, int>> acting;
  };

  Result evaluate(const std::vector<double> &x, int nlocal, bool newton) const
  {
    static const PeriSISSM::Model model = make_model();
    Result r;
    r.f.assign(3 * N, 0.0);
    r.block.assign(6 * N, 0.0);
    PeriSISSM::Particles p;
    p.nlocal = nlocal;
    p.nall = N;
    p.x = x.data();
    p.x0 = x0.data();
    p.volume = volume.data();
    p.type = type.data();
    p.f = r.f.data();
    PeriSISSM::ContactCandidates cand;
    cand.inum = nlocal;
    cand.ilist = ilist.data();
    cand.first = first.data();
    cand.neigh = neigh.data();
    Pairs pairs(volume);
    PeriSISSM::contact_pass(model, p, PeriSISSM::ReferenceBox(), 2.0, cand, newton, true, pairs,
                            r.block.data());
    r.energy = pairs.total;
    r.acting = pairs.acting_pairs;
    return r;
  }
};

// a configuration whose acting pairs do not change within the finite-difference steps (no pair
// within 1e-4 of its contact distance)
std::vector<double> away_from_kinks(const Cluster &c, unsigned seed)
{
  for (;; seed++) {
    const std::vector<double> x = c.squeezed(seed);
    bool ok = true;
    for (int i = 0; i < N && ok; i++)
      for (int j = i + 1; j < N && ok; j++) {
        double r2 = 0.0;
        for (int k = 0; k < 3; k++)
          r2 += (x[3 * i + k] - x[3 * j + k]) * (x[3 * i + k] - x[3 * j + k]);
        const double d = PeriSISSM::contact_distance(2.0, c.volume[i], c.volume[j]);
        if (std::fabs(std::sqrt(r2) - d) < 1e-4) ok = false;
      }
    if (ok) return x;
  }
}

// V_k f_k = -dE/dy_k of the energy the pass reports (central differences, step 1e-7 on gaps of
// ~0.1: error ~1e-8 of forces ~1; tolerance 1e-6 absolute)
TEST(ContactPass, ForcesAreMinusTheEnergyGradient)
{
  const Cluster c;
  const std::vector<double> x = away_from_kinks(c, 1u);
  const auto r = c.evaluate(x, N, true);
  EXPECT_GE(r.acting.size(), 6u);
  const auto energy = [&](const std::vector<double> &y) {
    return c.evaluate(y, N, true).energy;
  };
  double fmax = 0.0;
  for (int i = 0; i < N; i++)
    for (int k = 0; k < 3; k++) {
      const double dE = central_difference(energy, x, unit_direction(x.size(), 3 * i + k), 1e-7);
      EXPECT_NEAR(c.volume[i] * r.f[3 * i + k], -dE, 1e-6) << i << " " << k;
      fmax = std::max(fmax, std::fabs(dE));
    }
  EXPECT_GT(fmax, 0.1);
}

// block_i = -df_i/dy_i without the transverse stiffness kc V_j (1 - d/r) (I - n n^T) of each
// pair acting on i (negative in contact, left out to keep the block positive semi-definite):
// the derivative by central differences (step 1e-7: error ~1e-7 of entries ~1..10), the
// transverse parts from the pairs' geometry; tolerance 1e-5 absolute
TEST(ContactPass, BlocksAreTheDiagonalStiffnessWithoutItsTransversePart)
{
  const Cluster c;
  const PeriSISSM::Model model = make_model();
  const std::vector<double> x = away_from_kinks(c, 2u);
  const auto r = c.evaluate(x, N, true);
  const auto forces = [&](const std::vector<double> &y) {
    return c.evaluate(y, N, true).f;
  };
  std::vector<Eigen::Matrix3d> transverse(N, Eigen::Matrix3d::Zero());
  for (const auto &pair : r.acting) {
    const int i = pair.first, j = pair.second;
    const Eigen::Vector3d del(x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1],
                              x[3 * i + 2] - x[3 * j + 2]);
    const double dist = del.norm();
    const double d = PeriSISSM::contact_distance(2.0, c.volume[i], c.volume[j]);
    const double kc = model.kcontact(c.type[i], c.type[j]) / model.horizon(c.type[i], c.type[j]);
    const Eigen::Vector3d n = del / dist;
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    transverse[i] += kc * c.volume[j] * (1.0 - d / dist) * P;
    transverse[j] += kc * c.volume[i] * (1.0 - d / dist) * P;
  }
  double bmax = 0.0;
  for (int i = 0; i < N; i++) {
    const double *b = r.block.data() + 6 * i;
    Eigen::Matrix3d B;
    B << b[0], b[3], b[4], b[3], b[1], b[5], b[4], b[5], b[2];
    bmax = std::max(bmax, B.norm());
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(B).eigenvalues().minCoeff(),
              -1e-12 * B.norm())
        << i;
    for (int k = 0; k < 3; k++) {
      const std::vector<double> df =
          central_differences(forces, x, unit_direction(x.size(), 3 * i + k), 1e-7);
      for (int a = 0; a < 3; a++)
        EXPECT_NEAR(B(a, k) + transverse[i](a, k), -df[3 * i + a], 1e-5)
            << i << " " << a << " " << k;
    }
  }
  EXPECT_GT(bmax, 1.0);
}

// bonded pairs, pairs of types without contact and pairs beyond the contact distance do not
// act; every other pair does
TEST(ContactPass, WhichPairsAct)
{
  const Cluster c;
  const std::vector<double> x = away_from_kinks(c, 3u);
  const auto r = c.evaluate(x, N, true);
  int acting = 0;
  for (int i = 0; i < N; i++)
    for (int j = i + 1; j < N; j++) {
      double r2 = 0.0;
      for (int k = 0; k < 3; k++)
        r2 += (x[3 * i + k] - x[3 * j + k]) * (x[3 * i + k] - x[3 * j + k]);
      const double d = PeriSISSM::contact_distance(2.0, c.volume[i], c.volume[j]);
      const bool expect =
          std::sqrt(r2) < d && !(i == 0 && j == 1) && !(c.type[i] == 2 && c.type[j] == 2);
      EXPECT_EQ(r.acting.count({i, j}), expect ? 1u : 0u) << i << " " << j;
      acting += expect;
    }
  EXPECT_GE(acting, 6);
  EXPECT_LT(acting, N * (N - 1) / 2);
}

// rows >= nlocal are ghosts: with newton they get their share of a pair's force and block (for
// their owner), the same bits as when owned; without newton nothing
TEST(ContactPass, GhostRowsFollowNewton)
{
  const Cluster c;
  const std::vector<double> x = away_from_kinks(c, 4u);
  const auto all = c.evaluate(x, N, true);
  const int nlocal = 5;
  const auto on = c.evaluate(x, nlocal, true), off = c.evaluate(x, nlocal, false);
  // the candidates of owned particles hold every pair with an owned particle
  int ghost_rows_hit = 0;
  for (int i = nlocal; i < N; i++) {
    bool any = false;
    for (int m = 0; m < 6; m++) {
      EXPECT_EQ(off.block[6 * i + m], 0.0);
      any = any || on.block[6 * i + m] != 0.0;
    }
    for (int k = 0; k < 3; k++) EXPECT_EQ(off.f[3 * i + k], 0.0);
    ghost_rows_hit += any;
  }
  EXPECT_GT(ghost_rows_hit, 0);
  // owned rows: every pair with an owned particle was a candidate, so they get everything
  for (int i = 0; i < nlocal; i++) {
    for (int m = 0; m < 6; m++) {
      EXPECT_EQ(on.block[6 * i + m], all.block[6 * i + m]);
      EXPECT_EQ(off.block[6 * i + m], all.block[6 * i + m]);
    }
    for (int k = 0; k < 3; k++) EXPECT_EQ(on.f[3 * i + k], all.f[3 * i + k]);
  }
}

}    // namespace
