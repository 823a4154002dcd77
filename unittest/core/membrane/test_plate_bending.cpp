// Tests of the distributed plate bending list (membrane/plate_bending.h) on a jittered grid of
// alternate right triangles split between two "ranks" (each holds its owned vertices and the
// rest as ghosts): the ranks' forces and energies add up to the whole mesh's
// (membrane/curvature.h), bit for bit whatever the local order of the rows, the list finds the
// triangles of every owned vertex, and what it cannot build is reported.

#include "membrane/curvature.h"
#include "membrane/plate_bending.h"
#include "peri/bond_stiffness.h"

#include "flat_sheet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

using PeriSISSM::StencilStatus;

namespace {

// One rank's view: rows[r] the sheet vertex of row r (owned first), ID = vertex + 1, volume
// 1 + vertex / 100, every vertex a plate vertex of modulus D and Poisson's ratio nu.
class View : public PeriSISSM::HingeMesh {
 public:
  View(const Sheet &sheet, std::vector<int> owned, std::vector<int> ghosts, double D, double nu)
      : sheet_(sheet), nlocal_((int) owned.size()), D_(D), nu_(nu)
  {
    rows = owned;
    rows.insert(rows.end(), ghosts.begin(), ghosts.end());
    at_.resize(sheet.nv());
    for (const auto &t : sheet.tri)
      for (int k = 0; k < 3; k++) at_[t[k]].push_back({t[(k + 1) % 3] + 1, t[(k + 2) % 3] + 1});
    for (int r = 0; r < (int) rows.size(); r++) {
      row_of_[rows[r] + 1] = r;
      for (int d = 0; d < 3; d++) x0.push_back(sheet.X[3 * rows[r] + d]);
      volume.push_back(1.0 + rows[r] / 100.0);
    }
  }
  int nlocal() const override { return nlocal_; }
  std::int64_t id(int i) const override { return rows[i] + 1; }
  int ntri(int i) const override { return (int) at_[rows[i]].size(); }
  void triangle(int i, int k, std::int64_t &a, std::int64_t &b) const override
  {
    a = at_[rows[i]][k][0];
    b = at_[rows[i]][k][1];
  }
  int image(int, std::int64_t t) const override
  {
    const auto it = row_of_.find(t);
    return it == row_of_.end() ? -1 : it->second;
  }
  int sharer(std::int64_t t) const override
  {
    const int r = image(0, t);
    return r >= 0 && r < nlocal_ ? r : -1;
  }
  double modulus(int) const override { return D_; }
  bool plate(int) const override { return true; }
  double poisson(int) const override { return nu_; }

  std::vector<int> rows;
  std::vector<double> x0, volume;

 private:
  const Sheet &sheet_;
  int nlocal_;
  double D_, nu_;
  std::vector<std::vector<std::array<std::int64_t, 2>>> at_;
  std::map<std::int64_t, int> row_of_;
};

// The pass of one view at sheet positions y: forces (3 per sheet vertex, owned ones) and energy,
// with the list built by `plates` (a new one by default).
double view_pass(const View &view, const std::vector<double> &y, std::vector<double> &f_sheet,
                 PeriSISSM::PlateBending &&fresh = PeriSISSM::PlateBending(),
                 PeriSISSM::PlateBending *kept = nullptr)
{
  PeriSISSM::PlateBending &plates = kept ? *kept : fresh;
  PeriSISSM::ReferenceBox box;
  const PeriSISSM::PlateProblem problem = plates.build(view, view.x0.data(), box);
  EXPECT_TRUE(problem.ok());
  const int n = (int) view.rows.size();
  std::vector<double> x(3 * n), f(3 * n, 0.0);
  for (int r = 0; r < n; r++)
    for (int d = 0; d < 3; d++) x[3 * r + d] = y[3 * view.rows[r] + d];
  PeriSISSM::Particles p;
  p.nlocal = view.nlocal();
  p.nall = n;
  p.x = x.data();
  p.volume = view.volume.data();
  p.f = f.data();
  double E = 0.0;
  PeriSISSM::BendingEnergy energy;
  energy.total = &E;
  plates.pass(p, nullptr, energy, PeriSISSM::Virial());
  for (int r = 0; r < view.nlocal(); r++)
    for (int d = 0; d < 3; d++) f_sheet[3 * view.rows[r] + d] = f[3 * r + d] * view.volume[r];
  // (the energy tallies are densities: E / 3 / V of each corner)
  return E;
}

std::vector<double> bent_positions(const Sheet &sheet)
{
  std::vector<double> y = sheet.X;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < sheet.nv(); i++) {
    y[3 * i + 2] = 0.3 * std::sin(1.1 * y[3 * i]) * std::cos(0.8 * y[3 * i + 1]);
    for (int d = 0; d < 3; d++) y[3 * i + d] += 0.01 * u(rng);
  }
  return y;
}

}    // namespace

// Two ranks split at x = 0 give the whole mesh's forces (to round-off: the stencils are made
// in each triangle's own frame) and their energy shares add up to the whole energy.
TEST(PlateBending, TwoRanksAddUpToTheWholeMesh)
{
  const Sheet sheet(8, 6, 0.7, 0.2);
  const double D = 1.3, nu = 0.3;
  const std::vector<double> y = bent_positions(sheet);
  std::vector<PeriSISSM::CurvatureStencil> whole;
  ASSERT_TRUE(PeriSISSM::build_curvature_stencils(sheet.nv(), sheet.X.data(), sheet.tri, whole));
  std::vector<double> f_whole(y.size(), 0.0), fk;
  double E_whole = 0.0;
  for (const auto &s : whole) {
    fk.assign(3 * s.vertex.size(), 0.0);
    E_whole += PeriSISSM::curvature_energy(s, y.data(), D, nu, fk.data());
    for (std::size_t k = 0; k < s.vertex.size(); k++)
      for (int d = 0; d < 3; d++) f_whole[3 * s.vertex[k] + d] += fk[3 * k + d];
  }

  std::vector<int> left, right;
  for (int i = 0; i < sheet.nv(); i++) (sheet.X[3 * i] < 0.0 ? left : right).push_back(i);
  std::vector<double> f(y.size(), 0.0);
  // energy shares are densities: with every volume V_i, E = sum_T sum_corners E_T / 3 / V_c,
  // so compare against the same weighted sum of the whole mesh
  double E_weighted = 0.0;
  for (std::size_t t = 0; t < sheet.tri.size(); t++) {
    const double Et = PeriSISSM::curvature_energy(whole[t], y.data(), D, nu);
    for (int k = 0; k < 3; k++) E_weighted += Et / 3.0 / (1.0 + sheet.tri[t][k] / 100.0);
  }
  const double E =
      view_pass(View(sheet, left, right, D, nu), y, f) + view_pass(View(sheet, right, left, D, nu), y, f);
  EXPECT_NEAR(E, E_weighted, 1e-10 * E_weighted);
  EXPECT_GT(E_whole, 1e-3);
  double fmax = 0.0;
  for (double v : f_whole) fmax = std::max(fmax, std::abs(v));
  for (std::size_t j = 0; j < f.size(); j++) EXPECT_NEAR(f[j], f_whole[j], 1e-10 * fmax) << j;
}

// The rows of a view in another order give the same forces to the last bit (a restarted run
// sorts its atoms anew).
TEST(PlateBending, ForcesDoNotDependOnTheRowOrder)
{
  const Sheet sheet(6, 5, 1.0, 0.25);
  const std::vector<double> y = bent_positions(sheet);
  std::vector<int> all(sheet.nv());
  std::iota(all.begin(), all.end(), 0);
  std::vector<int> shuffled = all;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
  std::vector<double> f1(y.size(), 0.0), f2(y.size(), 0.0);
  const double E1 = view_pass(View(sheet, all, {}, 0.9, 0.2), y, f1);
  const double E2 = view_pass(View(sheet, shuffled, {}, 0.9, 0.2), y, f2);
  EXPECT_GT(E1, 0.0);
  for (std::size_t j = 0; j < f1.size(); j++) EXPECT_EQ(f1[j], f2[j]) << j;
  EXPECT_NEAR(E1, E2, 1e-13 * E1);    // (energies are summed in list order: corners differ)
}

// A list built again (as after every neighbor list build) with other rows and other owned
// vertices, from the candidates found by the first build, equals a list built afresh, bit for
// bit: the candidates are kept by vertex ID, the rows looked up anew.
TEST(PlateBending, BuiltAgainWithOtherRowsEqualsBuiltAfresh)
{
  const Sheet sheet(7, 6, 0.8, 0.2);
  const std::vector<double> y = bent_positions(sheet);
  std::vector<int> all(sheet.nv()), left, right;
  std::iota(all.begin(), all.end(), 0);
  for (int i = 0; i < sheet.nv(); i++) (sheet.X[3 * i] < 0.0 ? left : right).push_back(i);
  std::vector<int> shuffled = all;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
  PeriSISSM::PlateBending kept;
  std::vector<double> f0(y.size(), 0.0);
  view_pass(View(sheet, left, right, 1.1, 0.3), y, f0, PeriSISSM::PlateBending(), &kept);
  for (const View &view : {View(sheet, shuffled, {}, 1.1, 0.3), View(sheet, right, left, 1.1, 0.3),
                           View(sheet, all, {}, 1.1, 0.3)}) {
    std::vector<double> fa(y.size(), 0.0), fb(y.size(), 0.0);
    const double Ea = view_pass(view, y, fa, PeriSISSM::PlateBending(), &kept);
    const double Eb = view_pass(view, y, fb);
    EXPECT_GT(Eb, 0.0);
    EXPECT_EQ(Ea, Eb);
    for (std::size_t j = 0; j < fa.size(); j++) EXPECT_EQ(fa[j], fb[j]) << j;
  }
}

// What cannot be built is named: a rank whose ghosts stop one ring short of a stencil, and a
// mesh that is not flat at rest.
TEST(PlateBending, ReportsMissingVerticesAndCurvedMeshes)
{
  const Sheet sheet(8, 6, 1.0, 0.0);
  std::vector<int> left, near;
  for (int i = 0; i < sheet.nv(); i++) {
    if (sheet.X[3 * i] < -0.5)
      left.push_back(i);
    else if (sheet.X[3 * i] < 1.5)
      near.push_back(i);    // two columns of ghosts: too few
  }
  PeriSISSM::PlateBending plates;
  PeriSISSM::ReferenceBox box;
  const View short_view(sheet, left, near, 1.0, 0.0);
  PeriSISSM::PlateProblem problem = plates.build(short_view, short_view.x0.data(), box);
  EXPECT_EQ(problem.status, StencilStatus::missing);
  EXPECT_GE(problem.vertex, 1);

  Sheet curved(4, 4, 1.0, 0.0);
  curved.X[3 * 12 + 2] = 0.2;
  std::vector<int> all(curved.nv());
  std::iota(all.begin(), all.end(), 0);
  const View curved_view(curved, all, {}, 1.0, 0.0);
  PeriSISSM::PlateBending plates2;
  problem = plates2.build(curved_view, curved_view.x0.data(), box);
  EXPECT_EQ(problem.status, StencilStatus::not_flat);
}

// The couplings for the assembled stiffness factor each listed triangle's Hessian:
// a_k . a_l = h_kl (membrane/curvature.h curvature_hessian), with the rows and owners of the list.
TEST(PlateBending, CouplingsFactorTheHessian)
{
  const Sheet sheet(5, 4, 0.5, 0.2);
  std::vector<int> all(sheet.nv());
  std::iota(all.begin(), all.end(), 0);
  for (double nu : {0.0, 0.3, -0.5}) {
    const View view(sheet, all, {}, 1.7, nu);
    PeriSISSM::PlateBending plates;
    PeriSISSM::ReferenceBox box;
    ASSERT_TRUE(plates.build(view, view.x0.data(), box).ok());
    const PeriSISSM::PlateCouplings &c = plates.couplings();
    ASSERT_EQ(c.count(), (int) plates.triangles().size());
    ASSERT_EQ(c.count(), (int) sheet.tri.size());
    std::vector<double> h;
    for (int e = 0; e < c.count(); e++) {
      const PeriSISSM::PlateTriangle &t = plates.triangles()[e];
      PeriSISSM::curvature_hessian(t.stencil, t.D, t.nu, h);
      const int m = c.first[e + 1] - c.first[e];
      ASSERT_EQ(m, (int) t.stencil.vertex.size());
      for (int k = 0; k < m; k++) {
        EXPECT_EQ(c.vertex[c.first[e] + k], t.stencil.vertex[k]);
        EXPECT_EQ(c.row[c.first[e] + k], t.own[k]);
        for (int l = 0; l < m; l++) {
          const double *ak = &c.a[3 * (c.first[e] + k)], *al = &c.a[3 * (c.first[e] + l)];
          const double dot = ak[0] * al[0] + ak[1] * al[1] + ak[2] * al[2];
          EXPECT_NEAR(dot, h[m * k + l], 1e-12 * std::abs(h[m * k + k])) << e << k << l << nu;
        }
      }
    }
  }
}

// The pass's virial is sum_v y_v (x) F_v over the vertices (each element's forces sum to
// zero, so its parts relative to its first corner add up to that), and the per-atom parts add
// up to the global one.
TEST(PlateBending, VirialIsTheSumOfPositionsTimesForces)
{
  const Sheet sheet(5, 4, 0.5, 0.2);
  std::vector<int> all(sheet.nv());
  std::iota(all.begin(), all.end(), 0);
  const View view(sheet, all, {}, 1.1, 0.3);
  PeriSISSM::PlateBending plates;
  PeriSISSM::ReferenceBox box;
  ASSERT_TRUE(plates.build(view, view.x0.data(), box).ok());
  std::vector<double> y = bent_positions(sheet), f(y.size(), 0.0);
  for (std::size_t j = 0; j < y.size(); j++) y[j] += 3.0;    // away from the origin
  PeriSISSM::Particles p;
  p.nlocal = p.nall = sheet.nv();
  p.x = y.data();
  p.volume = view.volume.data();
  p.f = f.data();
  double global[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> rows(6 * sheet.nv(), 0.0);
  std::vector<double *> peratom(sheet.nv());
  for (int i = 0; i < sheet.nv(); i++) peratom[i] = &rows[6 * i];
  PeriSISSM::Virial virial;
  virial.global = global;
  virial.peratom = peratom.data();
  plates.pass(p, nullptr, PeriSISSM::BendingEnergy(), virial);
  double expected[6] = {0, 0, 0, 0, 0, 0}, summed[6] = {0, 0, 0, 0, 0, 0};
  const int a[6] = {0, 1, 2, 0, 0, 1}, b[6] = {0, 1, 2, 1, 2, 2};
  double scale = 0.0;
  for (int i = 0; i < sheet.nv(); i++)
    for (int m = 0; m < 6; m++) {
      const double F = f[3 * i + b[m]] * view.volume[i];
      expected[m] += y[3 * i + a[m]] * F;
      summed[m] += rows[6 * i + m];
      scale = std::max(scale, std::abs(y[3 * i + a[m]] * F));
    }
  ASSERT_GT(scale, 1e-3);
  for (int m = 0; m < 6; m++) {
    EXPECT_NEAR(global[m], expected[m], 1e-10 * scale) << m;
    EXPECT_NEAR(summed[m], global[m], 1e-12 * scale) << m;
  }
}
