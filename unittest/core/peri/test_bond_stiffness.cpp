// Tests of the bond-projected stiffness (peri/bond_stiffness): its springs are symmetric
// (k_ij = k_ji), the assembled matrix has the six rigid-body modes of the current positions as
// exact zero modes, and its calibration gives an interior particle of a regular lattice the
// material's P-wave modulus along any direction of uniaxial strain; membranes' bonds also carry
// the stabilization's block S_ij, symmetric positive semi-definite, with no stiffness along the
// normal of a flat sheet.

#include "cluster.h"

#include "materials/material.h"
#include "peri/bond_stiffness.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <vector>

namespace {

using PeriSISSMTest::Cluster;

PeriSISSM::Model linear_model(double bulk, double shear, double horizon)
{
  PeriSISSM::Model m;
  m.set_ntypes(1);
  const auto lame = PeriSISSM::lame_from_bulk_shear(bulk, shear);
  m.set_type(1, PeriSISSM::make_material("linear", lame.mu, lame.lambda), 0.0, bulk);
  m.set_pair(1, 1, horizon, false, 0.0);
  PeriSISSMTest::never_breaks(m, 1);
  return m;
}

PeriSISSM::BondSprings springs_of(Cluster &cl, const Cluster::Result &r)
{
  const PeriSISSM::Particles p = cl.particles(nullptr);
  PeriSISSM::ParticleFields fields;
  std::vector<double> k = r.k;
  fields.k = k.data();
  PeriSISSM::BondSprings s;
  PeriSISSM::bond_springs(cl.families(), p, fields, true, s);
  return s;
}

// a jittered cluster with unequal volumes, deformed by a rotation and a stretch
std::vector<double> deformed(const Cluster &cl)
{
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  S(0, 0) = 1.2;
  S(1, 2) = 0.1;
  std::vector<double> y(3 * cl.nlocal);
  for (int i = 0; i < cl.nlocal; i++) {
    const Eigen::Vector3d X(cl.x0[3 * i], cl.x0[3 * i + 1], cl.x0[3 * i + 2]);
    const Eigen::Vector3d Y = R * S * X;
    for (int k = 0; k < 3; k++) y[3 * i + k] = Y(k);
  }
  return y;
}

TEST(BondStiffness, SpringsAreSymmetric)
{
  const PeriSISSM::Model model = linear_model(1.0, 0.6, 1.8);
  Cluster cl(4, 3, 3, 1.8, false, 5);
  cl.build(model);
  const Cluster::Result r = cl.evaluate(model, deformed(cl));
  const PeriSISSM::BondSprings s = springs_of(cl, r);
  int pairs = 0;
  for (int i = 0; i < cl.nlocal; i++)
    for (int a = s.first[i]; a < s.first[i + 1]; a++) {
      const int j = s.partner[a];
      for (int b = s.first[j]; b < s.first[j + 1]; b++) {
        if (s.partner[b] != i) continue;
        pairs++;
        EXPECT_GT(s.k[a], 0.0);
        // same products in another order: a few ulps
        EXPECT_NEAR(s.k[a], s.k[b], 1e-14 * s.k[a]);
        for (int c = 0; c < 3; c++) EXPECT_NEAR(s.e[3 * a + c], -s.e[3 * b + c], 1e-15);
      }
    }
  EXPECT_GT(pairs, 100);
}

TEST(BondStiffness, RigidModesOfTheCurrentPositionsAreZeroModes)
{
  const PeriSISSM::Model model = linear_model(1.0, 0.6, 1.8);
  Cluster cl(4, 3, 3, 1.8, true, 7);
  cl.build(model);
  const Cluster::Result r = cl.evaluate(model, deformed(cl));
  const PeriSISSM::BondSprings s = springs_of(cl, r);
  // rows of the owned particles, applied to a displacement field u of all rows (ghosts are
  // images: their u is their owner's, translated or rotated with their own positions)
  for (int mode = 0; mode < 6; mode++) {
    std::vector<Eigen::Vector3d> u(cl.nall);
    double scale = 0.0;
    for (int i = 0; i < cl.nall; i++) {
      const Eigen::Vector3d X(cl.x[3 * i], cl.x[3 * i + 1], cl.x[3 * i + 2]);
      u[i] = mode < 3 ? Eigen::Vector3d::Unit(mode)
                      : Eigen::Vector3d(Eigen::Vector3d::Unit(mode - 3).cross(X));
    }
    for (int i = 0; i < cl.nlocal; i++) {
      Eigen::Vector3d out = Eigen::Vector3d::Zero();
      for (int a = s.first[i]; a < s.first[i + 1]; a++) {
        const Eigen::Vector3d e(s.e[3 * a], s.e[3 * a + 1], s.e[3 * a + 2]);
        out += s.k[a] * e * e.dot(u[s.partner[a]] - u[i]);
        scale = std::max(scale, s.k[a] * (u[s.partner[a]] - u[i]).norm());
      }
      EXPECT_LT(out.norm(), 1e-12 * std::max(scale, 1.0)) << "mode " << mode << " row " << i;
    }
  }
}

// Uniaxial strain eps n (x) n of an interior particle: the springs store
//   W_s = 1/(4 V_i) sum_j k_ij (e . eps xi)^2     (half of each bond to each end),
// and the calibration makes W_s = c/2 eps^2 with c the P-wave modulus 2 mu + lambda for an
// isotropic family. On a simple cubic lattice with horizon 3 spacings the family's fourth
// moment is nearly isotropic: within 5% along the axes, a face diagonal and a body diagonal.
TEST(BondStiffness, CalibratedToThePWaveModulus)
{
  const double bulk = 2.0, shear = 0.9, horizon = 3.0015;
  const PeriSISSM::Model model = linear_model(bulk, shear, horizon);
  Cluster cl(9, 9, 9, horizon, false, 1, 0.0, 0.0);
  cl.build(model);
  const Cluster::Result r = cl.evaluate(model, cl.x0);
  const PeriSISSM::BondSprings s = springs_of(cl, r);
  const int centre = (4 * 9 + 4) * 9 + 4;
  const auto lame = PeriSISSM::lame_from_bulk_shear(bulk, shear);
  const double c = 2.0 * lame.mu + lame.lambda;
  for (const Eigen::Vector3d &n :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0).normalized(),
        Eigen::Vector3d(1, 1, 1).normalized(), Eigen::Vector3d(0.3, -0.5, 0.8).normalized()}) {
    double w = 0.0;
    for (int a = s.first[centre]; a < s.first[centre + 1]; a++) {
      const int j = s.partner[a];
      Eigen::Vector3d xi;
      for (int k = 0; k < 3; k++) xi(k) = cl.x0[3 * j + k] - cl.x0[3 * centre + k];
      const Eigen::Vector3d e(s.e[3 * a], s.e[3 * a + 1], s.e[3 * a + 2]);
      const double stretch = e.dot(n) * n.dot(xi);    // e . (n n^T) xi, eps = 1
      w += s.k[a] * stretch * stretch;
    }
    w /= 4.0 * cl.volume[centre];
    EXPECT_NEAR(w, 0.5 * c, 0.05 * 0.5 * c) << "direction " << n.transpose();
  }
}

// Three particles by hand: 0 and 1 membrane particles (normals n0, n1), 2 without a normal;
// bonds 0-1, 0-2, 1-0, 2-0. S_ij = V_i omega_ij (C_i + C_j) / 2 (I - (n_a n_a^T + n_b n_b^T) / 2)
// (n_b = n_a at the end without a normal); none without normals at all.
TEST(BondStiffness, MembraneBondsCarryTheStabilizationBlock)
{
  constexpr int NK = PeriSISSM::ParticleFields::NK;
  double x[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, volume[3] = {2.0, 3.0, 5.0};
  int npartner[3] = {2, 1, 1};
  int j0[2] = {1, 2}, j1[1] = {0}, j2[1] = {0};
  int *jlocal[3] = {j0, j1, j2};
  double w0[2] = {0.5, 0.25}, w1[1] = {1.0 / 3.0}, w2[1] = {0.1};
  double *omega[3] = {w0, w1, w2};
  PeriSISSM::Families fam;
  fam.npartner = npartner;
  fam.jlocal = jlocal;
  fam.omega = omega;
  PeriSISSM::Particles p;
  p.nlocal = p.nall = 3;
  p.x = x;
  p.volume = volume;
  std::vector<double> k(3 * NK, 0.0);
  const double C[3] = {4.0, 6.0, 10.0};
  for (int i = 0; i < 3; i++) k[NK * i + PeriSISSM::ParticleFields::K_C] = C[i];
  const Eigen::Vector3d n0(0, 0, 1), n1 = Eigen::Vector3d(0.3, 0, 1).normalized();
  double normal[9] = {n0(0), n0(1), n0(2), n1(0), n1(1), n1(2), 0, 0, 0};
  PeriSISSM::ParticleFields fields;
  fields.k = k.data();
  fields.normal = normal;
  PeriSISSM::BondSprings s;
  PeriSISSM::bond_springs(fam, p, fields, true, s);
  ASSERT_EQ(s.k.size(), 4u);
  ASSERT_EQ(s.s.size(), 24u);

  auto block = [&](int t) {
    const double *v = &s.s[6 * t];
    Eigen::Matrix3d S;
    S << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    return S;
  };
  auto want = [&](int i, int j, double om, const Eigen::Vector3d &na, const Eigen::Vector3d &nb) {
    const Eigen::Matrix3d P =
        Eigen::Matrix3d::Identity() - 0.5 * (na * na.transpose() + nb * nb.transpose());
    return Eigen::Matrix3d(volume[i] * om * 0.5 * (C[i] + C[j]) * P);
  };
  const Eigen::Matrix3d S01 = block(0), S02 = block(1), S10 = block(2), S20 = block(3);
  EXPECT_LT((S01 - want(0, 1, 0.5, n0, n1)).norm(), 1e-14 * S01.norm());
  EXPECT_LT((S02 - want(0, 2, 0.25, n0, n0)).norm(), 1e-14 * S02.norm());
  EXPECT_LT((S10 - want(1, 0, 1.0 / 3.0, n1, n0)).norm(), 1e-14 * S10.norm());
  EXPECT_LT((S20 - want(2, 0, 0.1, n0, n0)).norm(), 1e-14 * S20.norm());
  // V_i omega_ij = V_j omega_ji for bond 0-1 (2 * 0.5 = 3 / 3): the same block from both ends
  EXPECT_LT((S01 - S10).norm(), 1e-14 * S01.norm());
  // positive semi-definite, at most its factor; a flat pair has no stiffness along its normal
  for (const Eigen::Matrix3d &S : {S01, S02, S10, S20}) {
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues();
    EXPECT_GE(ev(0), -1e-14 * S.norm());
  }
  EXPECT_NEAR((S02 * n0).norm(), 0.0, 1e-15);
  EXPECT_NEAR(S02(0, 0), volume[0] * 0.25 * 0.5 * (C[0] + C[2]), 1e-14);

  // the partners alone (the pattern): the same partners, no values
  PeriSISSM::BondSprings partners;
  PeriSISSM::bond_springs(fam, p, fields, false, partners);
  EXPECT_EQ(partners.first, s.first);
  EXPECT_EQ(partners.partner, s.partner);
  EXPECT_TRUE(partners.k.empty() && partners.e.empty() && partners.s.empty());

  // without normals (a deck without membranes): no blocks
  fields.normal = nullptr;
  PeriSISSM::bond_springs(fam, p, fields, true, s);
  EXPECT_EQ(s.k.size(), 4u);
  EXPECT_TRUE(s.s.empty());
}

}    // namespace
