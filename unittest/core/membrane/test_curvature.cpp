// Tests of the mid-edge shape operator (membrane/curvature.h) on grids of alternate right
// triangles, regular and jittered: exact plate energy for every quadratic deflection (boundary
// triangles included, at scales 1e-4 to 1e4), the energy of a sheet bent without stretching
// into a cylinder at any angle of its axis, no energy for rigid motions, forces against central
// differences, the Hessian against the forces, and the meshes it refuses.

#include "membrane/curvature.h"

#include "flat_sheet.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <random>
#include <vector>

using PeriSISSM::CurvatureStencil;

namespace {

std::vector<CurvatureStencil> stencils_of(const Sheet &s)
{
  std::vector<CurvatureStencil> out;
  EXPECT_TRUE(PeriSISSM::build_curvature_stencils(s.nv(), s.X.data(), s.tri, out));
  EXPECT_EQ(out.size(), s.tri.size());
  return out;
}

double total_energy(const std::vector<CurvatureStencil> &st, const std::vector<double> &y, double D,
                    double nu)
{
  double E = 0.0;
  for (const CurvatureStencil &s : st) E += PeriSISSM::curvature_energy(s, y.data(), D, nu);
  return E;
}

// the summed forces of all stencils, 3 per vertex
std::vector<double> forces(const std::vector<CurvatureStencil> &st, const std::vector<double> &y,
                           double D, double nu)
{
  std::vector<double> f(y.size(), 0.0), fk;
  for (const CurvatureStencil &s : st) {
    fk.assign(3 * s.vertex.size(), 0.0);
    PeriSISSM::curvature_energy(s, y.data(), D, nu, fk.data());
    for (std::size_t k = 0; k < s.vertex.size(); k++)
      for (int d = 0; d < 3; d++) f[3 * s.vertex[k] + d] += fk[3 * k + d];
  }
  return f;
}

}    // namespace

// w = 1/2 xi^T H xi + a . xi + b: every triangle's energy is A_T D/2 [(tr H)^2 - 2 (1 - nu)
// det H], at the rim too (its fits are least squares, exact on quadratics), at any scale.
TEST(Curvature, QuadraticDeflectionsAreExact)
{
  for (double h : {1e-4, 1.0, 1e4})
    for (double jitter : {0.0, 0.25}) {
      const Sheet sheet(6, 5, h, jitter);
      const std::vector<CurvatureStencil> st = stencils_of(sheet);
      const double hxx = 0.7 / (h * h), hxy = -0.3 / (h * h), hyy = 1.1 / (h * h);
      std::vector<double> y = sheet.X;
      for (int i = 0; i < sheet.nv(); i++) {
        const double x0 = sheet.X[3 * i], x1 = sheet.X[3 * i + 1];
        y[3 * i + 2] = 0.5 * (hxx * x0 * x0 + 2 * hxy * x0 * x1 + hyy * x1 * x1) + 0.2 * x0 -
            0.1 * x1 + 3.0 * h;
      }
      const double D = 2.5, nu = 0.3;
      const double density =
          0.5 * D * ((hxx + hyy) * (hxx + hyy) - 2.0 * (1.0 - nu) * (hxx * hyy - hxy * hxy));
      double area = 0.0;
      for (const CurvatureStencil &s : st) {
        EXPECT_NEAR(PeriSISSM::curvature_energy(s, y.data(), D, nu), s.area * density,
                    1e-9 * s.area * density)
            << h << " " << jitter;
        area += s.area;
      }
      EXPECT_NEAR(area, sheet.area, 1e-12 * sheet.area);
    }
}

// A sheet bent without stretching into a cylinder of curvature kappa (arc length u across the
// axis becomes sin(kappa u) / kappa in the plane and (1 - cos(kappa u)) / kappa out of it)
// stores D kappa^2 / 2 per area for every angle of the axis; measured 0.9980 to 0.9986 of it
// (kappa h = 0.1; the rest is the chords' departure from the arcs).
TEST(Curvature, CylinderAtAnyAngleStoresDKappaSquaredOverTwo)
{
  const double h = 0.1, kappa = 1.0, D = 1.7;
  for (double jitter : {0.0, 0.25}) {
    const Sheet sheet(12, 12, h, jitter);
    const std::vector<CurvatureStencil> st = stencils_of(sheet);
    for (double deg : {0.0, 30.0, 45.0, 60.0, 90.0}) {
      const double c = std::cos(deg * M_PI / 180.0), s = std::sin(deg * M_PI / 180.0);
      std::vector<double> y(sheet.X.size());
      for (int i = 0; i < sheet.nv(); i++) {
        const double x0 = sheet.X[3 * i], x1 = sheet.X[3 * i + 1];
        const double u = -s * x0 + c * x1, v = c * x0 + s * x1;
        const double across = std::sin(kappa * u) / kappa;
        y[3 * i] = c * v - s * across;
        y[3 * i + 1] = s * v + c * across;
        y[3 * i + 2] = (1.0 - std::cos(kappa * u)) / kappa;
      }
      for (double nu : {0.0, 0.3}) {
        const double ratio = total_energy(st, y, D, nu) / (0.5 * D * kappa * kappa * sheet.area);
        EXPECT_NEAR(ratio, 1.0, 2e-3) << jitter << " " << deg << " " << nu;
      }
    }
  }
}

// Rigid motions of the flat sheet cost nothing and give no forces; a rigid motion of a bent
// sheet keeps its energy.
TEST(Curvature, RigidMotionsCostNothing)
{
  const Sheet sheet(7, 6, 0.2, 0.25);
  const std::vector<CurvatureStencil> st = stencils_of(sheet);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(1.3, Eigen::Vector3d(0.4, -0.7, 1.0).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(5.0, -2.0, 0.7);
  auto moved = [&](const std::vector<double> &y) {
    std::vector<double> out(y.size());
    for (std::size_t i = 0; i < y.size(); i += 3) {
      const Eigen::Vector3d p = R * Eigen::Vector3d(y[i], y[i + 1], y[i + 2]) + shift;
      for (int d = 0; d < 3; d++) out[i + d] = p(d);
    }
    return out;
  };
  const std::vector<double> flat = moved(sheet.X);
  EXPECT_LT(total_energy(st, flat, 1.0, 0.3), 1e-22);
  for (double f : forces(st, flat, 1.0, 0.3)) EXPECT_LT(std::abs(f), 1e-10);

  std::vector<double> bent = sheet.X;
  for (int i = 0; i < sheet.nv(); i++)
    bent[3 * i + 2] = 0.3 * std::sin(1.1 * bent[3 * i]) * std::cos(0.8 * bent[3 * i + 1]);
  const double E = total_energy(st, bent, 1.0, 0.3);
  EXPECT_GT(E, 1e-3);
  EXPECT_NEAR(total_energy(st, moved(bent), 1.0, 0.3), E, 1e-12 * E);
}

// Forces against central differences of the energy (E is quadratic: central differences are
// exact up to round-off, at any step), at a random state.
TEST(Curvature, ForcesAreMinusTheEnergyGradient)
{
  const Sheet sheet(5, 4, 0.3, 0.25);
  const std::vector<CurvatureStencil> st = stencils_of(sheet);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y = sheet.X;
  for (double &c : y) c += 0.1 * u(rng);
  const double D = 0.8, nu = 0.25;
  const std::vector<double> f = forces(st, y, D, nu);
  double fmax = 0.0;
  for (double v : f) fmax = std::max(fmax, std::abs(v));
  ASSERT_GT(fmax, 0.1);
  for (double step : {1e-3, 1e-5})
    for (std::size_t j = 0; j < y.size(); j++) {
      std::vector<double> yp = y, ym = y;
      yp[j] += step;
      ym[j] -= step;
      const double g = (total_energy(st, yp, D, nu) - total_energy(st, ym, D, nu)) / (2 * step);
      EXPECT_NEAR(f[j], -g, 1e-7 * fmax) << j << " " << step;
    }
}

// The Hessian of each stencil against the change of its forces (exact: the forces are linear),
// symmetric and positive semi-definite.
TEST(Curvature, HessianIsTheForcesDerivative)
{
  const Sheet sheet(4, 4, 0.5, 0.2);
  const std::vector<CurvatureStencil> st = stencils_of(sheet);
  const double D = 1.3, nu = 0.3;
  std::vector<double> y = sheet.X;
  for (std::size_t i = 2; i < y.size(); i += 3) y[i] = 0.05 * y[i - 2] * y[i - 1];
  for (const CurvatureStencil &s : st) {
    const int m = (int) s.vertex.size();
    std::vector<double> h, f0(3 * m), f1(3 * m);
    PeriSISSM::curvature_hessian(s, D, nu, h);
    ASSERT_EQ((int) h.size(), m * m);
    PeriSISSM::curvature_energy(s, y.data(), D, nu, f0.data());
    for (int l = 0; l < m; l++)
      for (int d = 0; d < 3; d++) {
        std::vector<double> yp = y;
        yp[3 * s.vertex[l] + d] += 1.0;
        PeriSISSM::curvature_energy(s, yp.data(), D, nu, f1.data());
        for (int k = 0; k < m; k++)
          for (int e = 0; e < 3; e++) {
            const double expected = e == d ? h[m * k + l] : 0.0;
            EXPECT_NEAR(f0[3 * k + e] - f1[3 * k + e], expected, 1e-9 * std::abs(h[m * k + k]));
          }
      }
    Eigen::MatrixXd H = Eigen::Map<const Eigen::MatrixXd>(h.data(), m, m);
    EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().minCoeff(),
              -1e-12 * H.norm());
  }
}

// A mesh out of one plane, a degenerate triangle, and a strip one cell wide (its fits' points
// lie on two lines) are refused.
TEST(Curvature, RefusesMeshesItCannotFit)
{
  std::vector<CurvatureStencil> st;
  Sheet bent(3, 3, 1.0, 0.0);
  bent.X[3 * 5 + 2] = 0.1;
  EXPECT_FALSE(PeriSISSM::build_curvature_stencils(bent.nv(), bent.X.data(), bent.tri, st));
  EXPECT_TRUE(st.empty());
  Sheet flat(3, 3, 1.0, 0.0);
  flat.X[3 * 5] = flat.X[3 * 6];
  flat.X[3 * 5 + 1] = flat.X[3 * 6 + 1];
  EXPECT_FALSE(PeriSISSM::build_curvature_stencils(flat.nv(), flat.X.data(), flat.tri, st));
  const Sheet strip(6, 1, 1.0, 0.0);
  EXPECT_FALSE(PeriSISSM::build_curvature_stencils(strip.nv(), strip.X.data(), strip.tri, st));
}

// A sheet roughened out of its plane by 1e-3 of a cell (a random displacement before the first
// run) is taken as the flat sheet it approximates: its stencils are made from the projected rest
// positions and give the flat sheet's energies to the roughness' order; 2% of a cell is refused.
TEST(Curvature, SlightlyRoughSheetsAreTakenAsFlat)
{
  const Sheet flat(6, 6, 1.0, 0.2);
  Sheet rough = flat;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < rough.nv(); i++) rough.X[3 * i + 2] = 1e-3 * u(rng);
  const std::vector<CurvatureStencil> a = stencils_of(flat), b = stencils_of(rough);
  std::vector<double> y = flat.X;
  for (int i = 0; i < flat.nv(); i++)
    y[3 * i + 2] = 0.2 * std::sin(0.9 * y[3 * i]) + 0.1 * y[3 * i] * y[3 * i + 1];
  const double Ea = total_energy(a, y, 1.0, 0.3), Eb = total_energy(b, y, 1.0, 0.3);
  EXPECT_GT(Ea, 1e-3);
  EXPECT_NEAR(Eb, Ea, 1e-2 * Ea);
  for (int i = 0; i < rough.nv(); i++) rough.X[3 * i + 2] = 2e-2 * (i % 2 ? 1.0 : -1.0);
  std::vector<CurvatureStencil> st;
  EXPECT_FALSE(PeriSISSM::build_curvature_stencils(rough.nv(), rough.X.data(), rough.tri, st));
}
