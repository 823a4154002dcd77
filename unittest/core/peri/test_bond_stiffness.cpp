// Tests of the bond-projected stiffness (peri/bond_stiffness): its springs are symmetric
// (k_ij = k_ji), the assembled matrix has the six rigid-body modes of the current positions as
// exact zero modes, and its calibration gives an interior particle of a regular lattice the
// material's P-wave modulus along any direction of uniaxial strain.

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
  PeriSISSM::bond_springs(cl.families(), p, fields, s);
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

}    // namespace
