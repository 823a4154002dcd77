// Tests of the bending hinge (membrane/hinge.h): the dihedral angle's sign, range and gradient
// (finite differences, translation and rotation invariance), the energy's forces and blocks, and
// the calibration against a plate bent into a cylinder on meshes of equilateral and of right
// triangles.

#include "membrane/hinge.h"

#include "flat_sheet.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace {

using Vec = Eigen::Vector3d;

struct Quad {
  Vec x[4];
};

// a hinge folded by phi about the edge x0 = 0, x1 = e_x: triangle A (x2) stays in the plane
// z = 0 at y > 0 side... x2 = (0.4, 1, 0) has normal +z; x3 = (0.6, -1, 0) turned about the x
// axis by phi
Quad folded(double phi)
{
  Quad q;
  q.x[0] = Vec(0, 0, 0);
  q.x[1] = Vec(1, 0, 0);
  q.x[2] = Vec(0.4, 1.0, 0.0);
  q.x[3] = Vec(0.6, -std::cos(phi), std::sin(phi));
  return q;
}

double angle(const Quad &q, double g[4][3] = nullptr)
{
  return PeriSISSM::hinge_angle(q.x[0].data(), q.x[1].data(), q.x[2].data(), q.x[3].data(), g);
}

TEST(Hinge, AngleIsTheFoldAngle)
{
  EXPECT_EQ(angle(folded(0.0)), 0.0);
  for (double phi : {0.1, 0.7, 1.5, 2.5, 3.0, -0.4, -2.9}) {
    // folding x3 up (+z, the side the normals point to) by phi: a valley seen from +z, theta =
    // -phi
    EXPECT_NEAR(angle(folded(phi)), -phi, 1e-14) << phi;
  }
}

Quad random_quad(std::mt19937_64 &rng)
{
  std::normal_distribution<double> g;
  Quad q;
  for (auto &v : q.x) v = Vec(g(rng), g(rng), g(rng));
  return q;
}

// d theta / dx against central differences (step 1e-6, coordinates ~1: truncation ~1e-12,
// round-off ~1e-10), to 1e-7 absolute, on random hinges away from theta = +-pi (the branch cut)
TEST(Hinge, GradientMatchesFiniteDifferences)
{
  std::mt19937_64 rng(7);
  int tested = 0;
  for (int trial = 0; trial < 200 && tested < 60; trial++) {
    Quad q = random_quad(rng);
    double g[4][3];
    const double theta = angle(q, g);
    if (std::fabs(std::fabs(theta) - M_PI) < 0.2) continue;
    tested++;
    Vec sum = Vec::Zero();
    for (int v = 0; v < 4; v++) {
      sum += Vec(g[v][0], g[v][1], g[v][2]);
      for (int k = 0; k < 3; k++) {
        Quad p = q, m = q;
        p.x[v](k) += 1e-6;
        m.x[v](k) -= 1e-6;
        EXPECT_NEAR(g[v][k], (angle(p) - angle(m)) / 2e-6, 1e-7);
      }
    }
    EXPECT_LE(sum.norm(), 1e-12 * (1.0 + std::fabs(theta)));    // translation invariance
  }
  EXPECT_GE(tested, 60);
}

TEST(Hinge, RigidMotionsChangeNothing)
{
  std::mt19937_64 rng(11);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.2, Vec(1, -2, 0.5).normalized()).toRotationMatrix();
  const Vec t(3.0, -1.0, 7.0);
  for (int trial = 0; trial < 20; trial++) {
    const Quad q = random_quad(rng);
    Quad r;
    for (int v = 0; v < 4; v++) r.x[v] = R * q.x[v] + t;
    double gq[4][3], gr[4][3];
    EXPECT_NEAR(angle(q, gq), angle(r, gr), 1e-13);
    for (int v = 0; v < 4; v++)
      EXPECT_LE((R * Vec(gq[v][0], gq[v][1], gq[v][2]) - Vec(gr[v][0], gr[v][1], gr[v][2])).norm(),
                1e-11);
  }
}

// forces = -dE/dx (the angle's gradient is tested above; here the energy's factor 2 c (theta -
// theta0), the wrap of theta - theta0 across +-pi, and the blocks 2 c g g^T)
TEST(Hinge, EnergyForcesAndBlocks)
{
  const double c = 0.7;
  for (double theta0 : {0.0, 0.5, -3.0}) {
    for (double phi : {0.3, -1.0, 3.0}) {
      const Quad q = folded(phi);
      double f[4][3], blk[4][6], g[4][3];
      const double E = PeriSISSM::hinge_energy(q.x[0].data(), q.x[1].data(), q.x[2].data(),
                                               q.x[3].data(), theta0, c, f, blk);
      angle(q, g);
      double d = -phi - theta0;
      if (d > M_PI) d -= 2 * M_PI;
      if (d < -M_PI) d += 2 * M_PI;
      EXPECT_NEAR(E, c * d * d, 1e-13);
      for (int v = 0; v < 4; v++) {
        for (int k = 0; k < 3; k++) EXPECT_NEAR(f[v][k], -2 * c * d * g[v][k], 1e-13);
        EXPECT_NEAR(blk[v][0], 2 * c * g[v][0] * g[v][0], 1e-14);
        EXPECT_NEAR(blk[v][5], 2 * c * g[v][1] * g[v][2], 1e-14);
      }
    }
  }
}

// A flat mesh bent isometrically into a cylinder of curvature kappa (axis along `axis`, an
// in-plane direction): sum over interior edges of hinge energies with D = 1,
// per unit area of the interior, against kappa^2 / 2. Returns the ratio.
double cylinder_ratio(const std::vector<Vec> &X, const std::vector<std::array<int, 3>> &tri,
                      double kappa, double axis_angle)
{
  const Vec ax(std::cos(axis_angle), std::sin(axis_angle), 0.0);
  const Vec across(-ax(1), ax(0), 0.0);
  std::vector<Vec> Y(X.size());
  for (size_t i = 0; i < X.size(); i++) {
    const double s = X[i].dot(across), a = X[i].dot(ax);
    Y[i] = a * ax + std::sin(kappa * s) / kappa * across +
        Vec(0, 0, (1.0 - std::cos(kappa * s)) / kappa);
  }
  // interior edges: (a, b) -> third vertices of the triangle with a->b and of the one with b->a
  std::map<std::pair<int, int>, int> third;
  for (const auto &t : tri)
    for (int k = 0; k < 3; k++) third[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
  double energy = 0.0, area = 0.0;
  for (const auto &[edge, x2] : third) {
    const auto other = third.find({edge.second, edge.first});
    if (other == third.end()) continue;
    const Vec *x = X.data();
    const double c = PeriSISSM::hinge_stiffness(1.0, x[edge.first].data(), x[edge.second].data(),
                                                x[x2].data(), x[other->second].data());
    // each interior edge once
    if (edge.first > edge.second) continue;
    energy += PeriSISSM::hinge_energy(Y[edge.first].data(), Y[edge.second].data(), Y[x2].data(),
                                      Y[other->second].data(), 0.0, c);
    (void) area;
  }
  // the area the interior edges represent: each triangle counts once per interior edge / 3
  for (const auto &t : tri) {
    int interior = 0;
    for (int k = 0; k < 3; k++)
      if (third.count({t[(k + 1) % 3], t[k]})) interior++;
    area += interior / 3.0 * 0.5 * (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).norm();
  }
  return energy / area / (0.5 * kappa * kappa);
}

// equilateral triangles: rows of a triangular lattice
void equilateral(int n, std::vector<Vec> &X, std::vector<std::array<int, 3>> &tri)
{
  const double h = std::sqrt(3.0) / 2.0;
  for (int j = 0; j <= n; j++)
    for (int i = 0; i <= n; i++) X.emplace_back(i + 0.5 * (j % 2), j * h, 0.0);
  auto id = [n](int i, int j) {
    return j * (n + 1) + i;
  };
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      if (j % 2 == 0) {
        tri.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tri.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        tri.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        tri.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      }
    }
}

// right triangles, diagonals alternating from cell to cell (tools/make_sheet.py's default)
void alternate(int n, std::vector<Vec> &X, std::vector<std::array<int, 3>> &tri)
{
  for (int j = 0; j <= n; j++)
    for (int i = 0; i <= n; i++) X.emplace_back(i, j, 0.0);
  alternate_triangles(n, n, tri);
}

TEST(Hinge, CylinderCalibration)
{
  std::vector<Vec> X;
  std::vector<std::array<int, 3>> tri;
  equilateral(120, X, tri);
  // small curvature (kappa a = 0.01): the equilateral mesh gives D kappa^2 / 2 per unit area in
  // every direction of bending; the patch's boundary (edges at the rim counted with a third of
  // their triangles' area) leaves +-0.3% at 120 x 120 (it falls like 1/n): 0.5% allowed
  for (double ang : {0.0, 0.3, M_PI / 6, M_PI / 2}) {
    const double r = cylinder_ratio(X, tri, 0.01, ang);
    std::printf("equilateral, axis at %.3f rad: %.6f\n", ang, r);
    EXPECT_NEAR(r, 1.0, 5e-3) << ang;
  }
  std::vector<Vec> Y;
  std::vector<std::array<int, 3>> rt;
  alternate(120, Y, rt);
  // right triangles: the same along the grid lines, 1.5 x about a diagonal
  for (double ang : {0.0, M_PI / 4, M_PI / 2}) {
    const double r = cylinder_ratio(Y, rt, 0.01, ang);
    std::printf("right triangles (alternate), axis at %.3f rad: %.6f\n", ang, r);
    EXPECT_NEAR(r, ang == M_PI / 4 ? 1.5 : 1.0, 5e-3) << ang;
  }
}

}    // namespace
