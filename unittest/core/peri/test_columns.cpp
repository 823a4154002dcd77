// The 4-wide bond passes (ParticleFields::cols given, peri/columns.h, linalg/double4.h) against
// the scalar code of the fused version (cols not given): the same operations in the same order,
// so the same bits, in every case the passes distinguish: periodic or not, broken bonds, a
// particle with a singular shape tensor, without stabilization, energy and virial asked for or
// not, membranes, and the breaking check in both modes
// with one breaking rule for every pair and with a rule per type pair. Bitwise comparison: any
// difference at all fails. Skipped where the fused version does not run (no AVX2 and FMA, or a
// build without the dispatch), since both evaluations are then the plain scalar code.

#include "cluster.h"

#include "linalg/fused.h"
#include "materials/material.h"
#include "peri/elastic.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

using PeriSISSMTest::Cluster;

// K = 1, G = 0.6; ntypes types, horizon delta; bonds of type pair (i, j) break at
// s00 = 0.02 * (i + j) / 2 with alpha = 0.25 when breaking is set
PeriSISSM::Model make_model(const std::string &name, double cs, int ntypes, double delta,
                            bool membrane, bool breaking)
{
  PeriSISSM::Model m;
  m.set_ntypes(ntypes);
  const auto lame = PeriSISSM::lame_from_bulk_shear(1.0, 0.6);
  for (int t = 1; t <= ntypes; t++) {
    m.set_type(t, PeriSISSM::make_material(name, lame.mu, lame.lambda), cs, 1.0);
    if (membrane) m.set_membrane(t, true);
    for (int u = t; u <= ntypes; u++) m.set_pair(t, u, delta, false, 0.0);
  }
  m.breaking().configure(
      ntypes,
      [&](int, int) {
        return breaking;
      },
      [](int i, int j) {
        return 0.01 * (i + j);
      },
      [](int, int) {
        return 0.25;
      });
  return m;
}

// owned positions: the reference stretched by 1 + stretch along x, with noise
std::vector<double> moved(const Cluster &c, unsigned seed, double stretch, double noise)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(3 * c.nlocal);
  for (int i = 0; i < c.nlocal; i++)
    for (int k = 0; k < 3; k++)
      y[3 * i + k] = c.x0[3 * i + k] * (k == 0 ? 1.0 + stretch : 1.0) + noise * u(rng);
  return y;
}

template <class T> bool same_bits(const std::vector<T> &a, const std::vector<T> &b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same(const Cluster::Result &a, const Cluster::Result &b)
{
  EXPECT_TRUE(same_bits(a.f, b.f));
  EXPECT_TRUE(same_bits(a.g, b.g));
  EXPECT_TRUE(same_bits(a.h, b.h));
  EXPECT_TRUE(same_bits(a.k, b.k));
  EXPECT_TRUE(same_bits(a.blocks, b.blocks));
  EXPECT_EQ(std::memcmp(&a.energy, &b.energy, sizeof a.energy), 0);
  EXPECT_EQ(std::memcmp(a.virial, b.virial, sizeof a.virial), 0);
}

}    // namespace

// Whole evaluations (state, stabilization, force and SISSM blocks) of volume clusters, the
// stabilization in the vector form (Cs 1.5) and in the length form (Cs 2.5).
TEST(FourWidePasses, EvaluationHasTheBitsOfTheScalarCode)
{
  if (!PeriSISSM::fused_passes()) GTEST_SKIP() << "the fused version does not run here";
  for (const char *name : {"linear", "neohookean"})
    for (double cs : {0.0, 1.5, 2.5})
      for (bool periodic : {false, true})
        for (int flags = 0; flags < 4; flags++) {
          SCOPED_TRACE(std::string(name) + " cs " + std::to_string(cs) +
                       (periodic ? " periodic" : "") + " flags " + std::to_string(flags));
          PeriSISSM::Model model = make_model(name, cs, 1, 1.8, false, false);
          model.set_length_deviation(1, cs == 2.5);
          Cluster cl(4, 3, 3, 1.8, periodic, 11u);
          if (!periodic) cl.add_lonely(1.5);
          cl.build(model);
          for (int i = 0; i < cl.nlocal; i++)
            for (int b = i % 4; b < cl.npartner[i]; b += 9) cl.jl[i][b] = -1;
          cl.energy = flags & 1;
          cl.virial = flags & 2;
          const std::vector<double> y = moved(cl, 3u, 0.05, 0.08);
          cl.columns = true;
          const Cluster::Result wide = cl.evaluate(model, y);
          cl.columns = false;
          const Cluster::Result scalar = cl.evaluate(model, y);
          expect_same(wide, scalar);
          EXPECT_NE(wide.f[0], 0.0);
        }
}

// A membrane sheet (its stabilization counts z in the tangent planes only), with a particle of
// a single partner (singular: no F and no normal, so its bond takes the other end's normal)
// and broken bonds.
TEST(FourWidePasses, MembraneEvaluationHasTheBitsOfTheScalarCode)
{
  if (!PeriSISSM::fused_passes()) GTEST_SKIP() << "the fused version does not run here";
  const PeriSISSM::Model model = make_model("neohookean", 1.0, 1, 2.2, true, false);
  Cluster cl(5, 4, 1, 2.2, false, 7u, 0.15, 0.3);
  cl.add_lonely(2.0);
  for (int i = 0; i < cl.nlocal; i++) cl.normal.insert(cl.normal.end(), {0.0, 0.0, 1.0});
  cl.build(model);
  for (int i = 0; i < cl.nlocal; i++)
    for (int b = i % 3; b < cl.npartner[i]; b += 11) cl.jl[i][b] = -1;
  ASSERT_EQ(cl.kregular[cl.nlocal - 1], 0);
  std::vector<double> y = moved(cl, 5u, 0.03, 0.05);
  for (int i = 0; i < cl.nlocal; i++) y[3 * i + 2] += 0.05 * cl.x0[3 * i] * cl.x0[3 * i];
  cl.columns = true;
  const Cluster::Result wide = cl.evaluate(model, y);
  cl.columns = false;
  const Cluster::Result scalar = cl.evaluate(model, y);
  expect_same(wide, scalar);
}

// The state pass with the breaking check (BREAK and S0ONLY), one rule for all pairs (uniform:
// the comparison of squares, four bonds at a time where no slot is broken) and a rule per type
// pair: the same bonds break, the same s_min, F, H and W, bit for bit. Two identical clusters,
// one per version; some families have broken slots (so their bonds also go one at a time), and
// one particle's s_min is so large that the limit of its bonds is negative (all of them break).
TEST(FourWidePasses, BreakingCheckHasTheBitsOfTheScalarCode)
{
  if (!PeriSISSM::fused_passes()) GTEST_SKIP() << "the fused version does not run here";
  using PeriSISSM::BreakingRule;
  using PeriSISSM::ParticleFields;
  for (int ntypes : {1, 2})
    for (bool periodic : {false, true})
      for (int mode : {(int) BreakingRule::BREAK, (int) BreakingRule::S0ONLY}) {
        SCOPED_TRACE("ntypes " + std::to_string(ntypes) + (periodic ? " periodic" : "") + " mode " +
                     std::to_string(mode));
        const PeriSISSM::Model model = make_model("linear", 1.0, ntypes, 1.8, false, true);
        ASSERT_EQ(model.breaking().uniform(), ntypes == 1);
        struct Run {
          std::vector<int> jl, broke;
          std::vector<double> smin, g, h, w;
        } run[2];
        for (int v = 0; v < 2; v++) {
          Cluster cl(4, 4, 3, 1.8, periodic, 13u);
          for (int i = 0; i < cl.nall; i++) cl.type[i] = 1 + (i % ntypes);
          cl.build(model);
          for (int i = 0; i < cl.nall; i++) cl.smin[i] = 0.002 * (i % 5);
          cl.smin[5] = 10.0;
          for (int i = 0; i < cl.nlocal; i += 3)
            for (int b = i % 5; b < cl.npartner[i]; b += 7) cl.jl[i][b] = -1;
          cl.x = cl.positions_of(moved(cl, 9u, 0.02, 0.03));
          std::vector<double> f(3 * cl.nall), g(ParticleFields::NG * cl.nall), h(9 * cl.nall),
              w(cl.nall), sn(cl.nall), cols(ParticleFields::NCOLS * cl.nall);
          const PeriSISSM::Particles p = cl.particles(f.data());
          ParticleFields fields;
          fields.g = g.data();
          fields.h = h.data();
          fields.w = w.data();
          fields.smin_new = sn.data();
          fields.cols = v == 0 ? cols.data() : nullptr;
          PeriSISSM::elastic_state_pass(model, p, cl.families(), cl.box, mode, false, fields,
                                        run[v].broke);
          for (int i = 0; i < cl.nlocal; i++)
            run[v].jl.insert(run[v].jl.end(), cl.jl[i].begin(), cl.jl[i].end());
          run[v].smin = cl.smin;
          run[v].g = g;
          run[v].h = h;
          run[v].w = w;
        }
        if (mode == BreakingRule::BREAK)
          EXPECT_GT(run[0].broke.size(), 3u);
        else
          EXPECT_TRUE(run[0].broke.empty());
        EXPECT_EQ(run[0].broke, run[1].broke);
        EXPECT_EQ(run[0].jl, run[1].jl);
        EXPECT_TRUE(same_bits(run[0].smin, run[1].smin));
        EXPECT_TRUE(same_bits(run[0].g, run[1].g));
        EXPECT_TRUE(same_bits(run[0].h, run[1].h));
        EXPECT_TRUE(same_bits(run[0].w, run[1].w));
      }
}
