// Tests of the membrane correspondence (membrane/membrane.h) without LAMMPS: the tangent frame,
// the in-plane shape tensor, exactness for every affine map of the sheet (in-plane singular
// values of the map, thickness stretch of plane stress), rotation invariance, and the forces of
// flat sheets bent out of their plane against finite differences of the energy, for every model
// with and without stabilization.

#include "../peri/cluster.h"

#include "materials/material.h"
#include "membrane/membrane.h"
#include "peri/family.h"
#include "peri/particle.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

using PeriSISSMTest::Cluster;

// one membrane type: K = 1, G = 0.6 (nu = 0.25; xu: s0 = 1), horizon 2.2 spacings
PeriSISSM::Model make_model(const std::string &name, double cs)
{
  PeriSISSM::Model m;
  m.set_ntypes(1);
  if (name == "xu") {
    m.set_type(1, PeriSISSM::make_material(name, 1.0, 0.0), cs, 2.0 / 3.0);
  } else {
    const auto lame = PeriSISSM::lame_from_bulk_shear(1.0, 0.6);
    m.set_type(1, PeriSISSM::make_material(name, lame.mu, lame.lambda), cs, 1.0);
  }
  m.set_membrane(1, true);
  m.set_pair(1, 1, 2.2, false, 0.0);
  PeriSISSMTest::never_breaks(m, 1);
  return m;
}

Eigen::Matrix3d rotation(double angle, Eigen::Vector3d axis)
{
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// an nx x ny sheet of jittered particles in the plane z = 0, turned by R (its normal R e_z)
Cluster sheet(int nx, int ny, unsigned seed, const Eigen::Matrix3d &R)
{
  Cluster c(nx, ny, 1, 2.2, false, seed, 0.15, 0.3);
  const Eigen::Vector3d n = R.col(2);
  for (int i = 0; i < c.nlocal; i++) {
    const Eigen::Vector3d X(c.x0[3 * i], c.x0[3 * i + 1], 0.0);
    const Eigen::Vector3d Y = R * X;
    for (int k = 0; k < 3; k++) c.x0[3 * i + k] = Y(k);
    c.normal.insert(c.normal.end(), {n(0), n(1), n(2)});
  }
  c.x = c.positions_of(c.x0);
  c.ref = c.reference_of(c.x0);
  return c;
}

std::vector<double> mapped(const Cluster &c, const Eigen::Matrix3d &G)
{
  std::vector<double> y(3 * c.nlocal);
  for (int i = 0; i < c.nlocal; i++) {
    const Eigen::Vector3d Y = G * Eigen::Vector3d(c.x0[3 * i], c.x0[3 * i + 1], c.x0[3 * i + 2]);
    for (int k = 0; k < 3; k++) y[3 * i + k] = Y(k);
  }
  return y;
}

// the sheet bent out of its plane: a random near-identity map plus a smooth out-of-plane bulge
// and noise in every direction
std::vector<double> bent(const Cluster &c, unsigned seed, double noise)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) G(a, b) += 0.15 * u(rng);
  const Eigen::Vector3d n(c.normal[0], c.normal[1], c.normal[2]);
  std::vector<double> y = mapped(c, G);
  for (int i = 0; i < c.nlocal; i++) {
    const Eigen::Vector3d X(c.x0[3 * i], c.x0[3 * i + 1], c.x0[3 * i + 2]);
    const double bulge = 0.08 * X.squaredNorm();
    for (int k = 0; k < 3; k++) y[3 * i + k] += bulge * n(k) + noise * u(rng);
  }
  return y;
}

TEST(Membrane, TangentFrameIsRightHandedAndOrthonormal)
{
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  std::vector<Eigen::Vector3d> normals = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
  for (int k = 0; k < 20; k++) normals.emplace_back(g(rng), g(rng), g(rng));
  for (Eigen::Vector3d n : normals) {
    n.normalize();
    double t1[3], t2[3];
    PeriSISSM::tangent_frame(n.data(), t1, t2);
    const Eigen::Vector3d a(t1[0], t1[1], t1[2]), b(t2[0], t2[1], t2[2]);
    EXPECT_NEAR(a.norm(), 1.0, 1e-15);
    EXPECT_NEAR(b.norm(), 1.0, 1e-15);
    EXPECT_NEAR(a.dot(n), 0.0, 1e-15);
    EXPECT_NEAR(b.dot(n), 0.0, 1e-15);
    EXPECT_LE((a.cross(b) - n).norm(), 1e-15);
  }
}

// K^+ is the inverse of the projected shape tensor in the plane and annihilates the normal; a
// particle with partners on one line only is singular.
TEST(Membrane, InPlaneShapeTensor)
{
  const Eigen::Matrix3d R = rotation(0.7, {1.0, 2.0, 0.5});
  Cluster c = sheet(5, 5, 7u, R);
  const PeriSISSM::Model model = make_model("linear", 0.0);
  c.build(model);
  const Eigen::Vector3d n = R.col(2);
  const Eigen::Matrix3d T = Eigen::Matrix3d::Identity() - n * n.transpose();
  for (int i = 0; i < c.nlocal; i++) {
    ASSERT_EQ(c.kregular[i], 1) << i;
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    for (int b = 0; b < c.npartner[i]; b++) {
      const int j = c.jl[i][b];
      Eigen::Vector3d xi;
      for (int k = 0; k < 3; k++) xi(k) = c.ref[3 * j + k] - c.ref[3 * i + k];
      K += c.om[i][b] * xi * xi.transpose();
    }
    const Eigen::Matrix3d Kinv =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(c.kinv.data() + 9 * i);
    EXPECT_LE((Kinv * n).norm(), 1e-14 * Kinv.norm());
    EXPECT_LE((Kinv * K - T).norm(), 1e-12);
    EXPECT_LE((Kinv - Kinv.transpose()).norm(), 0.0);
  }
  // partners on a line
  double K[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0}, Kinv[9];
  const double ez[3] = {0, 0, 1};
  EXPECT_FALSE(PeriSISSM::invert_membrane_shape_tensor(K, ez, 0.0, Kinv));
  for (double v : Kinv) EXPECT_EQ(v, 0.0);
}

// Any affine map y = G X of the sheet: every particle's F agrees with G on the tangent plane,
// maps n0 to s3 n with n the unit normal of the image and s3 the plane-stress stretch, and W
// is the model's energy at the in-plane singular values of G and s3.
TEST(Membrane, AffineMapsAreExact)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d R = rotation(1.1, {0.3, -1.0, 0.4});
  const Eigen::Vector3d n0 = R.col(2), t1 = R.col(0), t2 = R.col(1);
  for (const std::string &name : PeriSISSM::material_names()) {
    SCOPED_TRACE(name);
    const PeriSISSM::Model model = make_model(name, 0.0);
    const auto &material = model.material(1);
    Cluster c = sheet(5, 4, 9u, R);
    c.build(model);
    for (int trial = 0; trial < 4; trial++) {
      Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) G(a, b) += 0.4 * u(rng);
      if (trial == 3) G = rotation(2.0, {1.0, 1.0, -2.0}) * G;    // plus a large rotation
      const Cluster::Result r = c.evaluate(model, mapped(c, G));
      Eigen::Matrix<double, 3, 2> image;
      image << G * t1, G * t2;
      const Eigen::Vector3d n = (G * t1).cross(G * t2).normalized();
      const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(image);
      const double s1 = svd.singularValues()(0), s2 = svd.singularValues()(1);
      const double s3 = material.plane_stress_stretch(s1, s2);
      const double W = material.energy(Eigen::Vector3d(s1, s2, s3));
      double energy = 0.0;
      for (int i = 0; i < c.nlocal; i++) energy += c.volume[i] * W;
      EXPECT_NEAR(r.energy, energy, 1e-11 * std::max(1.0, std::fabs(energy)));
      for (int i = 0; i < c.nlocal; i++) {
        const Eigen::Matrix3d F = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
            r.g.data() + PeriSISSM::ParticleFields::NG * i);
        EXPECT_LE((F * t1 - G * t1).norm(), 1e-12);
        EXPECT_LE((F * t2 - G * t2).norm(), 1e-12);
        EXPECT_LE((F * n0 - s3 * n).norm(), 1e-12);
      }
      // stress through the thickness vanishes: P n0 = phat3 n = 0
      const Eigen::Matrix3d F0 =
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.g.data());
      const Eigen::Matrix3d P = PeriSISSM::first_piola(material, F0);
      EXPECT_LE((P * n0).norm(), 1e-9 * std::max(1.0, P.norm()));
    }
  }
}

// A rigid rotation of a bent sheet changes neither the energy nor (up to the rotation) the forces.
TEST(Membrane, RotationInvariance)
{
  const Eigen::Matrix3d R = rotation(0.4, {1.0, 0.0, 1.0});
  const Eigen::Matrix3d Q = rotation(2.5, {-1.0, 2.0, 0.3});
  for (const std::string &name : PeriSISSM::material_names())
    for (double cs : {0.0, 1.5}) {
      SCOPED_TRACE(name + " Cs " + std::to_string(cs));
      const PeriSISSM::Model model = make_model(name, cs);
      Cluster c = sheet(5, 5, 13u, R);
      c.build(model);
      const std::vector<double> y = bent(c, 17u, 0.03);
      std::vector<double> yq(y.size());
      for (int i = 0; i < c.nlocal; i++) {
        const Eigen::Vector3d v = Q * Eigen::Vector3d(y[3 * i], y[3 * i + 1], y[3 * i + 2]);
        for (int k = 0; k < 3; k++) yq[3 * i + k] = v(k);
      }
      const Cluster::Result a = c.evaluate(model, y), b = c.evaluate(model, yq);
      EXPECT_NEAR(a.energy, b.energy, 1e-12 * std::fabs(a.energy));
      double fmax = 0.0, worst = 0.0;
      for (int i = 0; i < c.nlocal; i++) {
        const Eigen::Vector3d fa(a.f[3 * i], a.f[3 * i + 1], a.f[3 * i + 2]);
        const Eigen::Vector3d fb(b.f[3 * i], b.f[3 * i + 1], b.f[3 * i + 2]);
        fmax = std::max(fmax, fa.norm());
        worst = std::max(worst, (Q * fa - fb).norm());
      }
      ASSERT_GT(fmax, 1e-3);
      EXPECT_LE(worst, 1e-11 * fmax);
    }
}

// f_k = -(1/V_k) dE/dy_k for a flat sheet bent out of its plane, every model, Cs 0 and 1.5:
// central differences with step 1e-6 (spacing 1; truncation ~1e-12, round-off ~1e-10 |E|), to
// 1e-7 of the largest |V f| as for volumes (peri/test_terms.cpp).
TEST(Membrane, ForcesAreEnergyGradients)
{
  const Eigen::Matrix3d R = rotation(0.9, {0.2, 1.0, -0.7});
  for (const std::string &name : PeriSISSM::material_names())
    for (double cs : {0.0, 1.5}) {
      SCOPED_TRACE(name + " Cs " + std::to_string(cs));
      const PeriSISSM::Model model = make_model(name, cs);
      Cluster c = sheet(4, 4, 21u, R);
      c.build(model);
      const std::vector<double> y = bent(c, 23u, 0.04);
      const Cluster::Result r = c.evaluate(model, y);
      double fmax = 0.0;
      for (int i = 0; i < c.nlocal; i++)
        for (int k = 0; k < 3; k++) fmax = std::max(fmax, std::fabs(c.volume[i] * r.f[3 * i + k]));
      ASSERT_GT(fmax, 1e-3);
      const double step = 1e-6;
      double worst = 0.0;
      for (int i = 0; i < c.nlocal; i++)
        for (int k = 0; k < 3; k++) {
          std::vector<double> yp = y, ym = y;
          yp[3 * i + k] += step;
          ym[3 * i + k] -= step;
          const double dE =
              (c.evaluate(model, yp).energy - c.evaluate(model, ym).energy) / (2.0 * step);
          worst = std::max(worst, std::fabs(c.volume[i] * r.f[3 * i + k] + dE));
        }
      EXPECT_LE(worst, 1e-7 * fmax);
    }
}

// The implicit stiffness of a membrane particle has nothing along its current normal (the
// thickness direction carries no stress) and is symmetric positive semi-definite.
TEST(Membrane, ImplicitStiffnessLiesInThePlane)
{
  const Eigen::Matrix3d R = rotation(0.3, {1.0, 1.0, 0.0});
  for (const std::string &name : PeriSISSM::material_names()) {
    SCOPED_TRACE(name);
    const PeriSISSM::Model model = make_model(name, 0.0);
    Cluster c = sheet(4, 4, 29u, R);
    c.build(model);
    const Cluster::Result r = c.evaluate(model, bent(c, 31u, 0.02));
    for (int i = 0; i < c.nlocal; i++) {
      const double *k = r.k.data() + PeriSISSM::ParticleFields::NK * i;
      Eigen::Matrix3d H;
      H << k[0], k[3], k[4], k[3], k[1], k[5], k[4], k[5], k[2];
      const Eigen::Matrix3d F = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
          r.g.data() + PeriSISSM::ParticleFields::NG * i);
      const Eigen::Vector3d n = (F * R.col(0)).cross(F * R.col(1)).normalized();
      EXPECT_LE((H * n).norm(), 1e-12 * H.norm());
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
      EXPECT_GE(eig.eigenvalues()(0), -1e-12 * H.norm());
      EXPECT_GT(eig.eigenvalues()(2), 0.0);
    }
  }
}

// The stabilization of a membrane acts in its tangent planes only: a smooth out-of-plane bulge
// of amplitude e (non-affine across a family) costs it energy of order e^4 (from the rotation of
// the planes), where the whole residual would cost e^2. Doubling e from 1e-3 multiplies the
// energy by 2^4 = 16 within 1% (the e^6 terms are (2e)^2 ~ 1e-5 smaller); the unprojected
// residual's e^2 would give 4.
TEST(Membrane, StabilizationIgnoresBendingAtSecondOrder)
{
  const Eigen::Matrix3d R = rotation(0.6, {1.0, -0.5, 0.2});
  const PeriSISSM::Model model = make_model("linear", 2.0);
  Cluster c = sheet(6, 6, 37u, R);
  c.build(model);
  const Eigen::Vector3d n = R.col(2);
  auto energy = [&](double e) {
    std::vector<double> y = mapped(c, Eigen::Matrix3d::Identity());
    for (int i = 0; i < c.nlocal; i++) {
      const Eigen::Vector3d X(c.x0[3 * i], c.x0[3 * i + 1], c.x0[3 * i + 2]);
      const double bulge = e * std::cos(1.3 * X.dot(R.col(0))) * std::cos(0.9 * X.dot(R.col(1)));
      for (int k = 0; k < 3; k++) y[3 * i + k] += bulge * n(k);
    }
    return c.evaluate(model, y).energy;
  };
  const double e1 = energy(1e-3), e2 = energy(2e-3);
  ASSERT_GT(e1, 0.0);
  EXPECT_NEAR(e2 / e1, 16.0, 0.16);
}

}    // namespace
