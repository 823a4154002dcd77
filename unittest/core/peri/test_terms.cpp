// Tests of the energy terms of the peridynamic model (peri/elastic, peri/stabilization,
// peri/contact, evaluated as peri/forces orders them) on small clusters without LAMMPS:
// forces against finite differences of the energy (unequal volumes, a particle with a singular
// shape tensor, periodic images), the virial against the derivative of the energy by a
// homogeneous strain, and the diagonal blocks against the stiffness they stand for.

#include "cluster.h"

#include "materials/material.h"
#include "peri/contact.h"
#include "peri/elastic.h"
#include "peri/particle.h"
#include "peri/stabilization.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using PeriSISSMTest::Cluster;

// K = 1, G = 0.6 (nu = 0.25); horizon 1.6 spacings; length: the length form of the
// stabilization
PeriSISSM::Model make_model(const std::string &name, double cs, bool length = false)
{
  PeriSISSM::Model m;
  m.set_ntypes(1);
  const auto lame = PeriSISSM::lame_from_bulk_shear(1.0, 0.6);
  m.set_type(1, PeriSISSM::make_material(name, lame.mu, lame.lambda), cs, 1.0);
  m.set_length_deviation(1, length);
  m.set_pair(1, 1, 1.6, false, 0.0);
  PeriSISSMTest::never_breaks(m, 1);
  return m;
}

// owned positions of the cluster deformed by a random near-identity affine map and noise
std::vector<double> deformed(const Cluster &c, unsigned seed, double noise)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) A(a, b) += 0.15 * u(rng);
  std::vector<double> y(3 * c.nlocal);
  for (int i = 0; i < c.nlocal; i++) {
    const Eigen::Vector3d X(c.x0[3 * i], c.x0[3 * i + 1], c.x0[3 * i + 2]);
    const Eigen::Vector3d Y = A * X;
    for (int k = 0; k < 3; k++) y[3 * i + k] = Y(k) + noise * u(rng);
  }
  return y;
}

// the SISSM blocks of every owned particle of an evaluation, as matrices
std::vector<Eigen::Matrix3d> assembled_blocks(const Cluster::Result &r)
{
  std::vector<Eigen::Matrix3d> out(r.blocks.size() / 6);
  for (size_t i = 0; i < out.size(); i++) {
    const double *b = r.blocks.data() + 6 * i;
    out[i] << b[0], b[3], b[4], b[3], b[1], b[5], b[4], b[5], b[2];
  }
  return out;
}

struct Case {
  std::string model;
  double cs;
  bool periodic;
  bool length;    // the length form of the stabilization
  std::string name() const
  {
    return model + " Cs " + std::to_string(cs) + (length ? " length" : "") +
        (periodic ? " periodic" : "");
  }
};

std::vector<Case> cases()
{
  std::vector<Case> out;
  for (const std::string &name : PeriSISSM::material_names())
    for (double cs : {0.0, 1.5})
      for (bool periodic : {false, true})
        for (bool length : {false, true})
          if (cs > 0.0 || !length) out.push_back({name, cs, periodic, length});
  return out;
}

// f_k = -(1/V_k) dE/dy_k, E = sum_i V_i w_i, by central differences with step 1e-6 (spacing
// 1): truncation ~1e-12 |E'''|, round-off ~1e-16 |E| / 1e-6 = 1e-10 |E| with |E| ~ 1, both far
// below the tolerance, 1e-7 of the largest |V f| (|V f| ~ 0.1 here).
TEST(BondTerms, ForcesAreEnergyGradients)
{
  for (const Case &c : cases()) {
    SCOPED_TRACE(c.name());
    const PeriSISSM::Model model = make_model(c.model, c.cs, c.length);
    Cluster cl(c.periodic ? 5 : 3, 3, 3, 1.6, c.periodic, 11u);
    if (!c.periodic) cl.add_lonely(1.5);
    cl.build(model);
    if (!c.periodic) {
      EXPECT_EQ(cl.npartner[cl.nlocal - 1], 1);
      EXPECT_EQ(cl.kregular[cl.nlocal - 1], 0);    // the lonely particle has no F
    }
    const std::vector<double> y = deformed(cl, 5u, 0.04);
    const Cluster::Result r = cl.evaluate(model, y);
    double fmax = 0.0;
    for (int i = 0; i < cl.nlocal; i++)
      for (int k = 0; k < 3; k++) fmax = std::max(fmax, std::fabs(cl.volume[i] * r.f[3 * i + k]));
    ASSERT_GT(fmax, 1e-3);
    const double step = 1e-6;
    double worst = 0.0;
    for (int i = 0; i < cl.nlocal; i++)
      for (int k = 0; k < 3; k++) {
        std::vector<double> yp = y, ym = y;
        yp[3 * i + k] += step;
        ym[3 * i + k] -= step;
        const double dE =
            (cl.evaluate(model, yp).energy - cl.evaluate(model, ym).energy) / (2.0 * step);
        worst = std::max(worst, std::fabs(cl.volume[i] * r.f[3 * i + k] + dE));
      }
    EXPECT_LE(worst, 1e-7 * fmax);
  }
}

// Virial tallied by the passes (W_ab = sum over bonds, half to each end, of V_i (x_i - x_j)_a
// f_ij,b) against W_ba = -dE/deps_ab with y -> (I + eps e_a e_b^T) y: the tallies equal
// sum_k y_ka V_k f_kb because each bond's forces on its ends are equal and opposite, and
// dE/deps_ab = -sum_k V_k f_ka y_kb because the forces are the energy's gradient. Central
// differences with eps = 1e-6 on a body of size ~3: tolerance 1e-7 of the largest |W|.
TEST(BondTerms, VirialIsTheStrainDerivativeOfTheEnergy)
{
  for (const Case &c : cases()) {
    if (c.periodic) continue;    // (the images would have to be strained with the box)
    SCOPED_TRACE(c.name());
    const PeriSISSM::Model model = make_model(c.model, c.cs, c.length);
    Cluster cl(3, 3, 3, 1.6, false, 13u);
    cl.add_lonely(1.5);
    cl.build(model);
    const std::vector<double> y = deformed(cl, 7u, 0.04);
    const Cluster::Result r = cl.evaluate(model, y);
    const int ia[6] = {0, 1, 2, 0, 0, 1}, ib[6] = {0, 1, 2, 1, 2, 2};
    double wmax = 0.0;
    for (double w : r.virial) wmax = std::max(wmax, std::fabs(w));
    ASSERT_GT(wmax, 1e-3);
    for (int v = 0; v < 6; v++)
      for (int swap = 0; swap < 2; swap++) {
        const int a = swap ? ib[v] : ia[v], b = swap ? ia[v] : ib[v];
        const double eps = 1e-6;
        auto strained = [&](double e) {
          std::vector<double> ys = y;
          for (int i = 0; i < cl.nlocal; i++) ys[3 * i + a] += e * y[3 * i + b];
          return cl.evaluate(model, ys).energy;
        };
        const double dE = (strained(eps) - strained(-eps)) / (2.0 * eps);
        EXPECT_NEAR(r.virial[v], -dE, 1e-7 * wmax) << "component " << v << " a " << a << " b " << b;
      }
  }
}

// The length form of the stabilization stores, per bond, (Cbar / 2) omega V_i d^2 with
// d = (|eta|^2 - |Fbar xi|^2) / (2 |xi|) (a quarter at each end): the energy with Cs = 1.5 minus
// the energy without stabilization equals that sum computed here from the evaluation's F and C
// of every particle, to round-off (1e-12 of the sum); an affine deformation stores nothing.
TEST(BondTerms, LengthFormStoresTheBondLengthDeviation)
{
  const PeriSISSM::Model length = make_model("neohookean", 1.5, true);
  const PeriSISSM::Model none = make_model("neohookean", 0.0);
  Cluster cl(3, 3, 3, 1.6, false, 17u);
  cl.build(length);
  const std::vector<double> y = deformed(cl, 9u, 0.04);
  const Cluster::Result r = cl.evaluate(length, y);
  const double stored = r.energy - cl.evaluate(none, y).energy;
  constexpr int NG = PeriSISSM::ParticleFields::NG;
  double sum = 0.0;
  for (int i = 0; i < cl.nlocal; i++)
    for (int b = 0; b < cl.npartner[i]; b++) {
      const int j = cl.jl[i][b];
      const double *Fi = r.g.data() + NG * i, *Fj = r.g.data() + NG * j;
      Eigen::Vector3d e, xi, g = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; k++) {
        e(k) = cl.x[3 * j + k] - cl.x[3 * i + k];
        xi(k) = cl.ref[3 * j + k] - cl.ref[3 * i + k];
      }
      for (int a = 0; a < 3; a++)
        for (int k = 0; k < 3; k++) g(a) += 0.5 * (Fi[3 * a + k] + Fj[3 * a + k]) * xi(k);
      const double cbar =
          0.5 * (Fi[PeriSISSM::ParticleFields::G_C] + Fj[PeriSISSM::ParticleFields::G_C]);
      const double d = (e.squaredNorm() - g.squaredNorm()) / (2.0 * xi.norm());
      sum += 0.25 * cbar * cl.om[i][b] * cl.volume[i] * d * d;
    }
  ASSERT_GT(sum, 1e-8);
  EXPECT_NEAR(stored, sum, 1e-12 * std::fabs(sum) + 1e-15);
  const std::vector<double> affine = deformed(cl, 9u, 0.0);
  EXPECT_NEAR(cl.evaluate(length, affine).energy, cl.evaluate(none, affine).energy,
              1e-12 * std::fabs(cl.evaluate(none, affine).energy));
}

// The SISSM blocks: symmetric positive semi-definite for every model and state, and, where the
// split's linearization is exact, the stiffness of the implicit force. For an interior particle
// of a uniformly strained regular lattice whose partners all have complete (isotropic) families,
// K^-1 = kappa I, and the implicit force state omega U diag(c .* s) V^T K^-1 xi equals
// omega kappa U diag(c) U^T F xi = omega H^+ eta: then sum_j omega_ij (H^+_i + H^+_j) eta_ij (the
// block's force, linear in the positions) is exactly the implicit part of the elastic force
// sum_j omega_ij (A^+_i + A^+_j) xi_ij, A^+ = P^+ K^-1. Round-off: 1e-12 of the force scale.
TEST(BondTerms, BlocksAreTheImplicitStiffness)
{
  for (const std::string &name : PeriSISSM::material_names()) {
    SCOPED_TRACE(name);
    const PeriSISSM::Model model = make_model(name, 1.5);
    // symmetric PSD on a random cluster
    {
      Cluster cl(3, 3, 3, 1.6, false, 17u);
      cl.add_lonely(1.5);
      cl.build(model);
      const Cluster::Result r = cl.evaluate(model, deformed(cl, 9u, 0.04));
      const std::vector<Eigen::Matrix3d> blocks = assembled_blocks(r);
      for (int i = 0; i < cl.nlocal; i++) {
        const Eigen::Matrix3d &D = blocks[i];
        const double lo =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(D).eigenvalues().minCoeff();
        EXPECT_GE(lo, -1e-12 * D.norm()) << "particle " << i;
      }
    }
    // exact on the interior of a strained regular lattice
    {
      Cluster cl(5, 5, 5, 1.6, false, 1u, 0.0, 0.0);
      cl.build(model);
      Eigen::Matrix3d A;
      A << 1.02, 0.01, -0.005, 0.004, 0.985, 0.012, -0.007, 0.003, 1.01;
      std::vector<double> y(3 * cl.nlocal);
      for (int i = 0; i < cl.nlocal; i++) {
        const Eigen::Vector3d Y =
            A * Eigen::Vector3d(cl.x0[3 * i], cl.x0[3 * i + 1], cl.x0[3 * i + 2]);
        for (int k = 0; k < 3; k++) y[3 * i + k] = Y(k);
      }
      const Cluster::Result r = cl.evaluate(model, y);
      const int c = 2 * 25 + 2 * 5 + 2;    // the centre (2, 2, 2)
      constexpr int NK = PeriSISSM::ParticleFields::NK, NG = PeriSISSM::ParticleFields::NG;
      auto hplus = [&](int j) {
        const double *k = r.k.data() + NK * j;
        Eigen::Matrix3d H;
        H << k[0], k[3], k[4], k[3], k[1], k[5], k[4], k[5], k[2];
        return H;
      };
      auto aplus = [&](int j) {
        Eigen::Matrix3d F;
        for (int q = 0; q < 9; q++) F(q / 3, q % 3) = r.g[NG * j + q];
        PeriSISSM::ParticleStress ps;
        PeriSISSM::particle_stress(model.material(1), F, ps, true);
        Eigen::Matrix3d kinv;
        for (int q = 0; q < 9; q++) kinv(q / 3, q % 3) = cl.kinv[9 * j + q];
        return Eigen::Matrix3d(PeriSISSM::implicit_part(ps) * kinv);
      };
      Eigen::Vector3d fblock = Eigen::Vector3d::Zero(), fsplit = Eigen::Vector3d::Zero();
      for (int b = 0; b < cl.npartner[c]; b++) {
        const int j = cl.jl[c][b];
        const double w = cl.om[c][b];
        Eigen::Vector3d eta, xi;
        for (int k = 0; k < 3; k++) {
          eta(k) = y[3 * j + k] - y[3 * c + k];
          xi(k) = cl.x0[3 * j + k] - cl.x0[3 * c + k];
        }
        fblock += w * (hplus(c) + hplus(j)) * eta;
        fsplit += w * (aplus(c) + aplus(j)) * xi;
      }
      const double scale = (hplus(c).norm() * 1.6) * 10.0;
      EXPECT_LE((fblock - fsplit).norm(), 1e-12 * scale)
          << fblock.transpose() << " vs " << fsplit.transpose();
      // and the assembled block is minus the derivative of that force with respect to y_c,
      // plus the stabilization's (C_c + C_j)/2 omega I per bond (the stiffness of its direct
      // force with F held)
      Eigen::Matrix3d expect = Eigen::Matrix3d::Zero();
      for (int b = 0; b < cl.npartner[c]; b++) {
        const int j = cl.jl[c][b];
        const double w = cl.om[c][b];
        const double cbar = 0.5 *
            (r.g[NG * c + PeriSISSM::ParticleFields::G_C] +
             r.g[NG * j + PeriSISSM::ParticleFields::G_C]);
        expect += w * (hplus(c) + hplus(j)) + w * cbar * Eigen::Matrix3d::Identity();
      }
      const std::vector<Eigen::Matrix3d> blocks = assembled_blocks(r);
      const Eigen::Matrix3d &B = blocks[c];
      EXPECT_GT(r.g[NG * c + PeriSISSM::ParticleFields::G_C], 0.0);
      EXPECT_LE((B - expect).norm(), 1e-13 * expect.norm());
    }
  }
}

// The SISSM block of every owned particle is its sum over the unbroken bonds,
//   sum_j omega_ij (H+_i + H+_j + (C_i + C_j)/2 I),
// also where the evaluation sums several families side by side (the fused version goes four
// particles at a time: 27 particles leave three for the end, 3 x 3 x 4 plus a lonely particle
// one), with broken bonds (partner index -1, skipped) spread over them, in periodic and bounded
// boxes. Round-off: 1e-13 of the block.
TEST(BondTerms, BlocksOfEveryParticleSumTheUnbrokenBonds)
{
  const PeriSISSM::Model model = make_model("neohookean", 1.5);
  constexpr int NK = PeriSISSM::ParticleFields::NK, NG = PeriSISSM::ParticleFields::NG;
  for (int nz : {3, 4})
    for (bool periodic : {false, true}) {
      SCOPED_TRACE("nz " + std::to_string(nz) + (periodic ? " periodic" : ""));
      Cluster cl(3, 3, nz, 1.8, periodic, 5u + nz);
      if (nz == 4) cl.add_lonely(1.5);
      cl.build(model);
      int broken = 0;
      for (int i = 0; i < cl.nlocal; i++)
        for (int b = i % 5; b < cl.npartner[i]; b += 7) {
          cl.jl[i][b] = -1;
          broken++;
        }
      ASSERT_GT(broken, 10);
      const Cluster::Result r = cl.evaluate(model, deformed(cl, 3u, 0.05));
      auto hplus = [&](int j) {
        const double *k = r.k.data() + NK * j;
        Eigen::Matrix3d H;
        H << k[0], k[3], k[4], k[3], k[1], k[5], k[4], k[5], k[2];
        return H;
      };
      const std::vector<Eigen::Matrix3d> blocks = assembled_blocks(r);
      for (int i = 0; i < cl.nlocal; i++) {
        Eigen::Matrix3d expect = Eigen::Matrix3d::Zero();
        for (int b = 0; b < cl.npartner[i]; b++) {
          const int j = cl.jl[i][b];
          if (j < 0) continue;
          const double cbar = 0.5 *
              (r.g[NG * i + PeriSISSM::ParticleFields::G_C] +
               r.g[NG * j + PeriSISSM::ParticleFields::G_C]);
          expect += cl.om[i][b] * (hplus(i) + hplus(j) + cbar * Eigen::Matrix3d::Identity());
        }
        EXPECT_LE((blocks[i] - expect).norm(), 1e-13 * expect.norm() + 1e-300) << "particle " << i;
      }
    }
}

// Short-range contact of one pair: the force densities are -(1/V) dE/dy of the pair energy
// (unequal volumes), and the block is -df_i/dy_i without its transverse part
// kc V_j (1 - d/r) (I - n n^T), which is negative in contact: the block is kc V_j n n^T, positive
// semi-definite (derivatives by central differences, step 1e-7 on a gap of ~0.1: relative error
// ~1e-9; tolerance 1e-6).
TEST(Contact, PairForceAndBlockAreDerivatives)
{
  const double kc = 3.7, vi = 0.7, vj = 1.3;
  const double d = PeriSISSM::contact_distance(1.0, vi, vj);
  EXPECT_DOUBLE_EQ(d, 0.9);
  std::mt19937_64 rng(3u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 20; t++) {
    Eigen::Vector3d n(u(rng), u(rng), u(rng));
    n.normalize();
    const double r = d * (0.5 + 0.45 * (u(rng) + 1.0) / 2.0);
    const Eigen::Vector3d del = r * n;    // x_i - x_j
    auto energy = [&](const Eigen::Vector3d &dd) {
      return PeriSISSM::contact_energy(dd.norm(), d, kc, vi, vj);
    };
    auto force_i = [&](const Eigen::Vector3d &dd) {
      return Eigen::Vector3d(PeriSISSM::contact_fpair(dd.norm(), d, kc, vj) * dd);
    };
    const double step = 1e-7;
    const Eigen::Vector3d fi = force_i(del);
    double block[6];
    PeriSISSM::contact_block(del.data(), kc, vj, block);
    Eigen::Matrix3d B;
    B << block[0], block[3], block[4], block[3], block[1], block[5], block[4], block[5], block[2];
    for (int k = 0; k < 3; k++) {
      Eigen::Vector3d dp = del, dm = del;
      dp(k) += step;
      dm(k) -= step;
      const double dEi = (energy(dp) - energy(dm)) / (2.0 * step);    // dE/dy_i
      const double dEj = -dEi;                                        // dE/dy_j (del = y_i - y_j)
      EXPECT_NEAR(fi(k), -dEi / vi, 1e-6 * fi.norm());
      EXPECT_NEAR(-vi * fi(k) / vj, -dEj / vj, 1e-6 * fi.norm());    // f_j = -V_i f_i / V_j
      const Eigen::Vector3d col = -(force_i(dp) - force_i(dm)) / (2.0 * step);
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
      const Eigen::Vector3d transverse = kc * vj * (1.0 - d / r) * P.col(k);
      for (int a = 0; a < 3; a++) EXPECT_NEAR(B(a, k) + transverse(a), col(a), 1e-6 * B.norm());
    }
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(B).eigenvalues().minCoeff(),
              -1e-12 * B.norm());
    EXPECT_NEAR((B * n).norm(), kc * vj, 1e-12 * kc * vj);
    EXPECT_EQ(PeriSISSM::contact_energy(1.01 * d, d, kc, vi, vj), 0.0);
  }
}

}    // namespace

// pe of the bond terms: the densities summed in order into the total and added per particle,
// each sink optional.
TEST(EnergyTally, DensitiesIntoTotalAndPerParticle)
{
  const double w[3] = {1.5, -0.25, 1.0e-17};
  double total = 2.0, per[3] = {1.0, 1.0, 1.0};
  PeriSISSM::tally_energy_densities(3, w, &total, per);
  EXPECT_EQ(total, ((2.0 + 1.5) - 0.25) + 1.0e-17);
  EXPECT_EQ(per[0], 2.5);
  EXPECT_EQ(per[1], 0.75);
  EXPECT_EQ(per[2], 1.0 + 1.0e-17);
  PeriSISSM::tally_energy_densities(3, w, nullptr, per);
  EXPECT_EQ(per[0], 4.0);
  PeriSISSM::tally_energy_densities(3, w, &total, nullptr);
  EXPECT_EQ(total, (((2.0 + 1.5) - 0.25) + 1.0e-17 + 1.5) - 0.25 + 1.0e-17);
}
