// Tests of the bending term over a mesh (membrane/bending.h): the hinge list of a small curved
// mesh (each interior edge once, in the order of its IDs), the pass's forces against finite
// differences of its energy, its blocks against the Hessian at a rigidly moved rest shape, its
// virial against the strain derivative of the energy, the couplings against the blocks, and the
// same bits for the particles of a mesh split between two ranks as on one; the stable-step bound
// against the hinges' frequencies.

#include "membrane/bending.h"

#include "membrane/hinge.h"
#include "peri/bond_stiffness.h"
#include "peri/stable_step.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

using PeriSISSMTest::central_difference;
using PeriSISSMTest::central_differences;
using PeriSISSMTest::unit_direction;

namespace {

// A grid of NX x NY vertices cut into triangles along alternating diagonals, counter-clockwise
// seen from +z, with IDs that are a permutation of the grid order, a curved reference shape
// and unequal volumes and moduli.
struct Grid {
  static constexpr int NX = 5, NY = 4, N = NX * NY;
  std::vector<std::array<int, 3>> tri;    // grid indices
  std::vector<double> X;                  // reference positions, 3 per grid index
  std::vector<double> volume, modulus;
  std::vector<std::int64_t> id;

  Grid() : X(3 * N), volume(N), modulus(N), id(N)
  {
    for (int g = 0; g < N; g++) {
      const double x = g % NX, y = 0.9 * (g / NX) + 0.1 * (g % NX);
      X[3 * g] = x;
      X[3 * g + 1] = y;
      X[3 * g + 2] = 0.08 * (x - 2.0) * (x - 2.0) - 0.05 * x * y;
      volume[g] = 0.5 + 0.05 * g;
      modulus[g] = 1.0 + 0.1 * ((g * 3) % 7);
      id[g] = 1 + (g * 7) % N;    // 7 and N = 20 coprime: a permutation
    }
    for (int iy = 0; iy + 1 < NY; iy++)
      for (int ix = 0; ix + 1 < NX; ix++) {
        const int p00 = iy * NX + ix, p10 = p00 + 1, p01 = p00 + NX, p11 = p01 + 1;
        if ((ix + iy) % 2) {
          tri.push_back({p00, p10, p11});
          tri.push_back({p00, p11, p01});
        } else {
          tri.push_back({p00, p10, p01});
          tri.push_back({p10, p11, p01});
        }
      }
  }

  // interior edges (both triangles present), as unordered pairs of grid indices
  std::set<std::pair<int, int>> interior_edges() const
  {
    std::map<std::pair<int, int>, int> count;
    for (const auto &t : tri)
      for (int k = 0; k < 3; k++) {
        const int a = t[k], b = t[(k + 1) % 3];
        count[{std::min(a, b), std::max(a, b)}]++;
      }
    std::set<std::pair<int, int>> out;
    for (const auto &e : count)
      if (e.second == 2) out.insert(e.first);
    return out;
  }
};

// One rank's view of the grid: rows 0 .. nlocal-1 the owned vertices, then every other vertex
// as a ghost (rows[r] is the grid index of row r); every vertex takes shares.
class View : public PeriSISSM::HingeMesh {
 public:
  View(const Grid &grid, const std::vector<int> &owned) : grid_(grid), nlocal_((int) owned.size())
  {
    rows = owned;
    std::vector<bool> mine(Grid::N, false);
    for (int g : owned) mine[g] = true;
    for (int g = 0; g < Grid::N; g++)
      if (!mine[g]) rows.push_back(g);
    for (int r = 0; r < (int) rows.size(); r++) row_of_[grid.id[rows[r]]] = r;
    tris_.resize(rows.size());
    for (const auto &t : grid.tri)
      for (int k = 0; k < 3; k++) {
        const int g = t[k];
        for (int r = 0; r < (int) rows.size(); r++)
          if (rows[r] == g) tris_[r].push_back({grid.id[t[(k + 1) % 3]], grid.id[t[(k + 2) % 3]]});
      }
    for (int r = 0; r < (int) rows.size(); r++) {
      const int g = rows[r];
      for (int d = 0; d < 3; d++) x0.push_back(grid.X[3 * g + d]);
      volume.push_back(grid.volume[g]);
    }
  }
  int nlocal() const override { return nlocal_; }
  std::int64_t id(int i) const override { return grid_.id[rows[i]]; }
  int ntri(int i) const override { return (int) tris_[i].size(); }
  void triangle(int i, int k, std::int64_t &a, std::int64_t &b) const override
  {
    a = tris_[i][k].first;
    b = tris_[i][k].second;
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
  double modulus(int i) const override { return grid_.modulus[rows[i]]; }

  // a view that lacks vertex ID t (neither owned nor ghost)
  void forget(std::int64_t t) { row_of_.erase(t); }

  std::vector<int> rows;
  std::vector<double> x0, volume;

 private:
  const Grid &grid_;
  int nlocal_;
  std::map<std::int64_t, int> row_of_;
  std::vector<std::vector<std::pair<std::int64_t, std::int64_t>>> tris_;
};

struct Evaluation {
  std::vector<double> f, block, energy;    // per owned row
  double total = 0.0;
  double virial[6] = {0, 0, 0, 0, 0, 0};
};

// the pass over the hinges of view at positions x (3 per row)
Evaluation evaluate(const View &view, const std::vector<PeriSISSM::Hinge> &hinges,
                    const std::vector<double> &x)
{
  const int n = view.nlocal();
  Evaluation ev;
  ev.f.assign(3 * view.rows.size(), 0.0);
  ev.block.assign(6 * n, 0.0);
  ev.energy.assign(n, 0.0);
  std::vector<double *> rows(n);
  for (int i = 0; i < n; i++) rows[i] = ev.block.data() + 6 * i;
  PeriSISSM::Particles p;
  p.nlocal = n;
  p.nall = (int) view.rows.size();
  p.x = x.data();
  p.x0 = view.x0.data();
  p.volume = view.volume.data();
  p.f = ev.f.data();
  PeriSISSM::BendingEnergy energy;
  energy.total = &ev.total;
  energy.per_particle = ev.energy.data();
  PeriSISSM::Virial virial;
  virial.global = ev.virial;
  PeriSISSM::bending_pass(hinges, p, rows.data(), energy, virial);
  return ev;
}

// the energy itself: sum_i V_i (energy density share of i)
double total_energy(const View &view, const std::vector<PeriSISSM::Hinge> &hinges,
                    const std::vector<double> &x)
{
  const Evaluation ev = evaluate(view, hinges, x);
  double E = 0.0;
  for (int i = 0; i < view.nlocal(); i++) E += view.volume[i] * ev.energy[i];
  return E;
}

std::vector<int> all_vertices()
{
  std::vector<int> out(Grid::N);
  for (int g = 0; g < Grid::N; g++) out[g] = g;
  return out;
}

// positions of the grid moved away from its reference shape (random, amplitude a)
std::vector<double> perturbed(const std::vector<double> &x0, double a, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x = x0;
  for (double &c : x) c += a * u(rng);
  return x;
}

TEST(Bending, EachInteriorEdgeOnceInTheOrderOfItsIds)
{
  const Grid grid;
  const View view(grid, all_vertices());
  std::vector<PeriSISSM::Hinge> hinges;
  EXPECT_EQ(PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges), 0);
  const auto edges = grid.interior_edges();
  ASSERT_EQ(hinges.size(), edges.size());
  std::set<std::pair<int, int>> seen;
  for (size_t h = 0; h < hinges.size(); h++) {
    const auto &hg = hinges[h];
    const int a = view.rows[hg.v[0]], b = view.rows[hg.v[1]];
    EXPECT_LT(grid.id[a], grid.id[b]);
    seen.insert({std::min(a, b), std::max(a, b)});
    if (h > 0) {
      const auto &prev = hinges[h - 1];
      const std::pair<std::int64_t, std::int64_t> p{grid.id[view.rows[prev.v[0]]],
                                                    grid.id[view.rows[prev.v[1]]]};
      EXPECT_LT(p, std::make_pair(grid.id[a], grid.id[b]));
    }
    for (int k = 0; k < 4; k++) EXPECT_EQ(hg.own[k], hg.v[k]);
    // the rest angle and stiffness of the hinge's reference shape, D the mean of the edge's ends
    const double *X[4];
    for (int k = 0; k < 4; k++) X[k] = view.x0.data() + 3 * hg.v[k];
    EXPECT_DOUBLE_EQ(hg.theta0, PeriSISSM::hinge_angle(X[0], X[1], X[2], X[3]));
    const double D = 0.5 * (grid.modulus[a] + grid.modulus[b]);
    EXPECT_DOUBLE_EQ(hg.c, PeriSISSM::hinge_stiffness(D, X[0], X[1], X[2], X[3]));
    EXPECT_NE(hg.theta0, 0.0);
  }
  EXPECT_EQ(seen, edges);
}

// V_i f_i = -dE/dx_i by central differences (step 1e-6 on coordinates ~1: truncation ~1e-12,
// round-off ~1e-10 of energies ~0.1; tolerance 1e-7 absolute on forces ~0.1..1), and the sum
// of the energy shares times their volumes is the energy of all hinges
TEST(Bending, ForcesAreMinusTheEnergyGradient)
{
  const Grid grid;
  const View view(grid, all_vertices());
  std::vector<PeriSISSM::Hinge> hinges;
  PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges);
  const std::vector<double> x = perturbed(view.x0, 0.15, 5u);
  const Evaluation ev = evaluate(view, hinges, x);
  const auto energy = [&](const std::vector<double> &y) {
    return total_energy(view, hinges, y);
  };
  double sum = 0.0;
  for (const auto &h : hinges)
    sum += PeriSISSM::hinge_energy(&x[3 * h.v[0]], &x[3 * h.v[1]], &x[3 * h.v[2]], &x[3 * h.v[3]],
                                   h.theta0, h.c);
  EXPECT_NEAR(total_energy(view, hinges, x), sum, 1e-14 * sum);
  EXPECT_GT(sum, 1e-3);
  double fmax = 0.0;
  for (int i = 0; i < Grid::N; i++)
    for (int k = 0; k < 3; k++) {
      const double dE = central_difference(energy, x, unit_direction(x.size(), 3 * i + k), 1e-6);
      EXPECT_NEAR(view.volume[i] * ev.f[3 * i + k], -dE, 1e-7) << i << " " << k;
      fmax = std::max(fmax, std::fabs(dE));
    }
  EXPECT_GT(fmax, 1e-2);
}

// At a rigidly moved rest shape theta = theta0, where the Hessian of c (theta - theta0)^2 is
// its Gauss-Newton part 2 c g g^T: block_i = -df_i/dx_i by central differences of the forces
// (step 1e-6: error ~1e-9 of entries ~0.1..1; tolerance 1e-6 absolute)
TEST(Bending, BlocksAreTheHessianAtRest)
{
  const Grid grid;
  const View view(grid, all_vertices());
  std::vector<PeriSISSM::Hinge> hinges;
  PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -1.0, 0.6).normalized()).toRotationMatrix();
  std::vector<double> x(view.x0.size());
  for (int i = 0; i < Grid::N; i++) {
    const Eigen::Vector3d y =
        R * Eigen::Vector3d(view.x0[3 * i], view.x0[3 * i + 1], view.x0[3 * i + 2]) +
        Eigen::Vector3d(2.0, -1.0, 0.5);
    for (int k = 0; k < 3; k++) x[3 * i + k] = y(k);
  }
  const Evaluation ev = evaluate(view, hinges, x);
  const auto forces = [&](const std::vector<double> &y) {
    return evaluate(view, hinges, y).f;
  };
  double bmax = 0.0;
  for (int i = 0; i < Grid::N; i++) {
    const double *b = ev.block.data() + 6 * i;
    Eigen::Matrix3d B;
    B << b[0], b[3], b[4], b[3], b[1], b[5], b[4], b[5], b[2];
    bmax = std::max(bmax, B.norm());
    for (int k = 0; k < 3; k++) {
      const std::vector<double> df =
          central_differences(forces, x, unit_direction(x.size(), 3 * i + k), 1e-6);
      for (int a = 0; a < 3; a++)
        EXPECT_NEAR(B(a, k), -df[3 * i + a], 1e-6) << i << " " << a << " " << k;
    }
  }
  EXPECT_GT(bmax, 0.1);
}

// The virial sum_v (x_v - x_0) (x) F_v (xx yy zz xy xz yz, entry (a, b) = sum r_a F_b) against
// -dE/d eps of the homogeneous deformation x_b += eps x_a (central differences, step 1e-6;
// tolerance 1e-7 absolute)
TEST(Bending, VirialIsTheStrainDerivative)
{
  const Grid grid;
  const View view(grid, all_vertices());
  std::vector<PeriSISSM::Hinge> hinges;
  PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges);
  const std::vector<double> x = perturbed(view.x0, 0.15, 9u);
  const Evaluation ev = evaluate(view, hinges, x);
  const auto energy = [&](const std::vector<double> &y) {
    return total_energy(view, hinges, y);
  };
  const int comp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  double wmax = 0.0;
  for (int m = 0; m < 6; m++) {
    const int a = comp[m][0], b = comp[m][1];
    std::vector<double> strain(x.size(), 0.0);
    for (int i = 0; i < Grid::N; i++) strain[3 * i + b] = x[3 * i + a];
    const double dE = central_difference(energy, x, strain, 1e-6);
    EXPECT_NEAR(ev.virial[m], -dE, 1e-7) << m;
    wmax = std::max(wmax, std::fabs(dE));
  }
  EXPECT_GT(wmax, 1e-2);
}

// The couplings' diagonal parts sum_h g_v g_v^T (g = sqrt(2 c) grad theta) are the pass's
// blocks times the volume, and their rows are where the pass puts each share
TEST(Bending, CouplingsMatchTheBlocks)
{
  const Grid grid;
  const View view(grid, all_vertices());
  std::vector<PeriSISSM::Hinge> hinges;
  PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges);
  const std::vector<double> x = perturbed(view.x0, 0.15, 13u);
  const Evaluation ev = evaluate(view, hinges, x);
  PeriSISSM::Particles p;
  p.nlocal = p.nall = Grid::N;
  p.x = x.data();
  PeriSISSM::HingeCouplings cp;
  PeriSISSM::hinge_couplings(hinges, p, false, cp);
  EXPECT_EQ(cp.count(), (int) hinges.size());
  EXPECT_TRUE(cp.grad.empty());
  PeriSISSM::hinge_couplings(hinges, p, true, cp);
  ASSERT_EQ(cp.grad.size(), 12 * hinges.size());
  std::vector<Eigen::Matrix3d> sum(Grid::N, Eigen::Matrix3d::Zero());
  for (int h = 0; h < cp.count(); h++)
    for (int v = 0; v < 4; v++) {
      EXPECT_EQ(cp.vertex[4 * h + v], hinges[h].v[v]);
      EXPECT_EQ(cp.row[4 * h + v], hinges[h].own[v]);
      const Eigen::Vector3d g(&cp.grad[12 * h + 3 * v]);
      sum[cp.row[4 * h + v]] += g * g.transpose();
    }
  for (int i = 0; i < Grid::N; i++) {
    const double *b = ev.block.data() + 6 * i;
    Eigen::Matrix3d B;
    B << b[0], b[3], b[4], b[3], b[1], b[5], b[4], b[5], b[2];
    EXPECT_LE((view.volume[i] * B - sum[i]).norm(), 1e-13 * sum[i].norm() + 1e-300) << i;
  }
}

// The grid split between two ranks (each with every other vertex as a ghost): each vertex gets
// the same force, block and energy share to the last bit as on one rank
TEST(Bending, TwoRanksGiveTheBitsOfOne)
{
  const Grid grid;
  std::vector<int> first, second;
  // the lower two rows of the grid and the upper two, the owned rows of each in reverse order
  for (int g = Grid::N - 1; g >= 0; g--) (g < Grid::N / 2 ? first : second).push_back(g);
  const View one(grid, all_vertices()), ra(grid, first), rb(grid, second);
  std::vector<PeriSISSM::Hinge> h1, ha, hb;
  PeriSISSM::build_hinges(one, one.x0.data(), PeriSISSM::ReferenceBox(), h1);
  PeriSISSM::build_hinges(ra, ra.x0.data(), PeriSISSM::ReferenceBox(), ha);
  PeriSISSM::build_hinges(rb, rb.x0.data(), PeriSISSM::ReferenceBox(), hb);
  EXPECT_LT(ha.size(), h1.size());
  EXPECT_LT(hb.size(), h1.size());
  EXPECT_GT(ha.size() + hb.size(), h1.size());    // straddling hinges on both
  const std::vector<double> x = perturbed(one.x0, 0.15, 17u);
  auto rows_of = [&](const View &v) {
    std::vector<double> out(3 * v.rows.size());
    for (size_t r = 0; r < v.rows.size(); r++)
      for (int k = 0; k < 3; k++) out[3 * r + k] = x[3 * v.rows[r] + k];
    return out;
  };
  const Evaluation e1 = evaluate(one, h1, x);
  for (const View *v : {&ra, &rb}) {
    const Evaluation ev = evaluate(*v, v == &ra ? ha : hb, rows_of(*v));
    for (int r = 0; r < v->nlocal(); r++) {
      const int g = v->rows[r];
      for (int k = 0; k < 3; k++) EXPECT_EQ(ev.f[3 * r + k], e1.f[3 * g + k]);
      for (int m = 0; m < 6; m++) EXPECT_EQ(ev.block[6 * r + m], e1.block[6 * g + m]);
      EXPECT_EQ(ev.energy[r], e1.energy[g]);
    }
    // no force on a ghost row
    for (size_t r = v->nlocal(); r < v->rows.size(); r++)
      for (int k = 0; k < 3; k++) EXPECT_EQ(ev.f[3 * r + k], 0.0);
  }
}

// A hinge with a vertex that is not on this rank is reported by the ID of an owned vertex
TEST(Bending, MissingVertexIsReported)
{
  const Grid grid;
  std::vector<int> owned = {Grid::NX + 1};    // an interior vertex
  View view(grid, owned);
  view.forget(grid.id[Grid::NX + 2]);    // its neighbor along x
  std::vector<PeriSISSM::Hinge> hinges;
  EXPECT_EQ(PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges),
            grid.id[Grid::NX + 1]);
  View whole(grid, owned);
  EXPECT_EQ(PeriSISSM::build_hinges(whole, whole.x0.data(), PeriSISSM::ReferenceBox(), hinges), 0);
}

}    // namespace

// The stable-step bound: the largest squared frequency of the hinges' Hessian at rest over the
// vertices' masses (rho_i V_i) is at most max_i G_i / rho_i, and the estimate of G_i alone
// (kStableStepSafety sqrt(2 rho / G)) stays below the limit 2 / omega of central differences;
// combined with an elastic estimate it is the estimate of the summed stiffness.
TEST(Bending, StableStepBoundsTheHingeFrequencies)
{
  const Grid grid;
  const View view(grid, all_vertices());
  std::vector<PeriSISSM::Hinge> hinges;
  PeriSISSM::build_hinges(view, view.x0.data(), PeriSISSM::ReferenceBox(), hinges);
  const int n = Grid::N;
  std::vector<double> rho(n), dt(n, std::numeric_limits<double>::infinity()), G(n, 0.0);
  for (int i = 0; i < n; i++) rho[i] = 800.0 + 50.0 * ((i * 5) % 3);
  PeriSISSM::Particles p;
  p.nlocal = n;
  p.nall = n;
  p.x = view.x0.data();
  p.volume = view.volume.data();
  PeriSISSM::bending_stable_steps(hinges, p, rho.data(), dt.data(), G.data());

  // the Gauss-Newton Hessian K = sum 2 c g g^T and the lumped masses
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (const PeriSISSM::Hinge &h : hinges) {
    double g[4][3];
    const double *x = view.x0.data();
    PeriSISSM::hinge_angle(x + 3 * h.v[0], x + 3 * h.v[1], x + 3 * h.v[2], x + 3 * h.v[3], g);
    for (int a = 0; a < 4; a++)
      for (int b = 0; b < 4; b++)
        for (int r = 0; r < 3; r++)
          for (int c = 0; c < 3; c++)
            K(3 * h.v[a] + r, 3 * h.v[b] + c) += 2.0 * h.c * g[a][r] * g[b][c];
  }
  Eigen::VectorXd minv(3 * n);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) minv(3 * i + k) = 1.0 / std::sqrt(rho[i] * view.volume[i]);
  const Eigen::MatrixXd S = minv.asDiagonal() * K * minv.asDiagonal();
  const double omega2 = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().maxCoeff();
  double bound = 0.0, dtmin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; i++) {
    bound = std::max(bound, G[i] / rho[i]);
    dtmin = std::min(dtmin, dt[i]);
    EXPECT_DOUBLE_EQ(dt[i], PeriSISSM::stable_time_step(rho[i], G[i])) << i;
  }
  ASSERT_GT(omega2, 0.0);
  EXPECT_GE(bound, omega2);
  // how far the bound is from the frequency on this curved, uneven grid: measured 1.59, and
  // the smallest estimate 0.70 times the limit 2 / omega
  EXPECT_LT(bound, 2.0 * omega2);
  EXPECT_LT(dtmin, 0.9 * 2.0 / std::sqrt(omega2));
  EXPECT_GT(dtmin, 0.5 * 2.0 / std::sqrt(omega2));

  // with an elastic estimate of d_e: the estimate of d_e + G_i
  std::vector<double> dt2(n), G2(n, 0.0);
  for (int i = 0; i < n; i++) dt2[i] = PeriSISSM::stable_time_step(rho[i], 3.0 * G[i] + 1.0);
  PeriSISSM::bending_stable_steps(hinges, p, rho.data(), dt2.data(), G2.data());
  for (int i = 0; i < n; i++) {
    EXPECT_EQ(G2[i], G[i]);
    EXPECT_NEAR(dt2[i], PeriSISSM::stable_time_step(rho[i], 4.0 * G[i] + 1.0), 1e-14 * dt2[i]);
  }
}
