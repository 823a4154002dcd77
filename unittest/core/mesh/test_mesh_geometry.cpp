// Geometry of read_mesh: placement (scale, rotate, offset in that order), triangle and vertex
// areas, and angle-weighted vertex normals against hand computations, at extreme scales too.
#include "mesh/mesh_geometry.h"
#include "vertex_storage.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace PeriSISSM;

namespace {

constexpr double kPi = 3.14159265358979323846;

void expect_vector(const double *a, double x, double y, double z, double tol)
{
  EXPECT_NEAR(a[0], x, tol);
  EXPECT_NEAR(a[1], y, tol);
  EXPECT_NEAR(a[2], z, tol);
}

}    // namespace

TEST(MeshGeometry, PlacementScalesThenRotatesThenShifts)
{
  Placement p;
  p.scale = 2.0;
  p.theta = 90.0;    // about +z: x -> y
  p.offset[0] = 1.0;
  p.offset[1] = 1.0;
  p.offset[2] = 1.0;
  const double X[3] = {1.0, 0.0, 0.5};
  double x[3];
  place(p, X, x);
  expect_vector(x, 1.0, 3.0, 2.0, 1e-15);

  // 120 degrees about (1,1,1) (any length) cycles the axes x -> y -> z
  Placement q;
  q.theta = 120.0;
  q.axis[0] = q.axis[1] = q.axis[2] = 7.0;
  const double ex[3] = {1.0, 0.0, 0.0}, ey[3] = {0.0, 1.0, 0.0};
  place(q, ex, x);
  expect_vector(x, 0.0, 1.0, 0.0, 1e-15);
  place(q, ey, x);
  expect_vector(x, 0.0, 0.0, 1.0, 1e-15);

  // no keyword: the file's coordinates
  const double Y[3] = {0.1, -2.0, 3.0e5};
  place(Placement(), Y, x);
  expect_vector(x, 0.1, -2.0, 3.0e5, 0.0);
}

TEST(MeshGeometry, VertexAreasOfAGridAreCornerEdgeAndInteriorShares)
{
  // 5 x 4 vertices spaced h, two triangles per cell (diagonal from (i,j) to (i+1,j+1))
  const int nx = 5, ny = 4;
  const double h = 0.25;
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) v.push_back({i * h, j * h, 0.0});
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      const int a = j * nx + i;
      t.push_back({a, a + 1, a + nx + 1});
      t.push_back({a, a + nx + 1, a + nx});
    }
  const auto area = vertex_areas(v, t);
  const double cell = h * h, tri = cell / 2.0;
  double sum = 0.0;
  for (double a : area) sum += a;
  EXPECT_NEAR(sum, (nx - 1) * (ny - 1) * cell, 1e-15);
  EXPECT_NEAR(area[0], 2 * tri / 3, 1e-16);             // two triangles at (0,0)
  EXPECT_NEAR(area[nx - 1], 1 * tri / 3, 1e-16);        // one at (4,0)
  EXPECT_NEAR(area[2], 3 * tri / 3, 1e-16);             // bottom edge: three
  EXPECT_NEAR(area[1 * nx + 2], 6 * tri / 3, 1e-16);    // interior: six
  EXPECT_NEAR(area[(ny - 1) * nx + nx - 1], 2 * tri / 3, 1e-16);
}

TEST(MeshGeometry, TriangleArea)
{
  const double a[3] = {0, 0, 0}, b[3] = {3, 0, 0}, c[3] = {0, 4, 5};
  EXPECT_NEAR(triangle_area(a, b, c), 0.5 * 3 * std::sqrt(41.0), 1e-14);
}

TEST(MeshGeometry, FlatFanNormalFollowsTheOrientation)
{
  // an interior vertex of a flat, counterclockwise fan of 6 unequal triangles
  const double xi[3] = {0.2, -0.1, 3.0};
  const double angles[6] = {0.0, 0.7, 1.9, 2.5, 3.6, 5.0};
  double up[3] = {0, 0, 0}, down[3] = {0, 0, 0};
  for (int k = 0; k < 6; k++) {
    const double a0 = angles[k], a1 = angles[(k + 1) % 6] + (k == 5 ? 2 * kPi : 0.0);
    const double r0 = 1.0 + 0.1 * k, r1 = 1.0 + 0.1 * ((k + 1) % 6);
    const double xa[3] = {xi[0] + r0 * std::cos(a0), xi[1] + r0 * std::sin(a0), xi[2]};
    const double xb[3] = {xi[0] + r1 * std::cos(a1), xi[1] + r1 * std::sin(a1), xi[2]};
    add_angle_weighted_normal(xi, xa, xb, up);
    add_angle_weighted_normal(xi, xb, xa, down);
  }
  expect_vector(up, 0.0, 0.0, 2 * kPi, 1e-14);    // the angles sum to a full turn
  ASSERT_TRUE(normalize_or_zero(up));
  ASSERT_TRUE(normalize_or_zero(down));
  expect_vector(up, 0.0, 0.0, 1.0, 1e-15);
  expect_vector(down, 0.0, 0.0, -1.0, 1e-15);
}

TEST(MeshGeometry, CubeCornerNormalIsTheDiagonal)
{
  // three right-angled triangles at the corner of a cube (outward: -x, -y, -z faces seen from
  // outside are counterclockwise), each weighted by pi/2
  const double o[3] = {0, 0, 0}, ex[3] = {2, 0, 0}, ey[3] = {0, 3, 0}, ez[3] = {0, 0, 1};
  double n[3] = {0, 0, 0};
  add_angle_weighted_normal(o, ey, ex, n);    // normal -z
  add_angle_weighted_normal(o, ex, ez, n);    // normal -y
  add_angle_weighted_normal(o, ez, ey, n);    // normal -x
  expect_vector(n, -kPi / 2, -kPi / 2, -kPi / 2, 1e-15);
  normalize_or_zero(n);
  const double s = 1.0 / std::sqrt(3.0);
  expect_vector(n, -s, -s, -s, 1e-15);
}

TEST(MeshGeometry, FoldedVertexNormalByHand)
{
  // vertex at the origin on a fold along y: triangle 1 in the xy plane (angle 90 deg at the
  // vertex, normal +z), triangle 2 rises at 60 degrees (angle 45 deg at the vertex)
  const double o[3] = {0, 0, 0}, a[3] = {1, 0, 0}, b[3] = {0, 1, 0};
  const double c[3] = {-0.5, 1.0, std::sqrt(3.0) / 2};    // (-cos 60, 1, sin 60) * 1
  double n[3] = {0, 0, 0};
  add_angle_weighted_normal(o, a, b, n);
  add_angle_weighted_normal(o, b, c, n);
  // triangle 2: e1 = (0,1,0), e2 = c; e1 x e2 = (sqrt3/2, 0, 1/2); |e2| = sqrt2, angle 45 deg
  const double w1 = kPi / 2, w2 = kPi / 4;
  expect_vector(n, w2 * std::sqrt(3.0) / 2, 0.0, w1 + w2 * 0.5, 1e-15);
}

TEST(MeshGeometry, NormalsDoNotDependOnTheScale)
{
  const double xi[3] = {0.1, 0.2, 0.3}, xa[3] = {1.3, 0.1, 0.2}, xb[3] = {0.2, 1.1, 0.9};
  double ref[3] = {0, 0, 0};
  add_angle_weighted_normal(xi, xa, xb, ref);
  normalize_or_zero(ref);
  for (double s : {1e-8, 1e8}) {
    const double si[3] = {s * xi[0], s * xi[1], s * xi[2]};
    const double sa[3] = {s * xa[0], s * xa[1], s * xa[2]};
    const double sb[3] = {s * xb[0], s * xb[1], s * xb[2]};
    double n[3] = {0, 0, 0};
    add_angle_weighted_normal(si, sa, sb, n);
    normalize_or_zero(n);
    expect_vector(n, ref[0], ref[1], ref[2], 1e-15);
  }
}

TEST(MeshGeometry, DegenerateTriangleAddsNothingAndZeroStaysZero)
{
  const double xi[3] = {0, 0, 0}, xa[3] = {1, 0, 0}, xb[3] = {2, 0, 0};
  double n[3] = {0, 0, 0};
  add_angle_weighted_normal(xi, xa, xb, n);
  EXPECT_FALSE(normalize_or_zero(n));
  expect_vector(n, 0, 0, 0, 0);
}

TEST(MeshGeometry, ClosestImageFollowsTheSametagChain)
{
  // one atom at rows 1, 3 and 4 (images one box length 10 apart), row 0 elsewhere
  const double rows[5][3] = {{0, 0, 0}, {9.5, 0, 0}, {5, 5, 5}, {-0.5, 0, 0}, {9.5, 10, 0}};
  const double *x[5] = {rows[0], rows[1], rows[2], rows[3], rows[4]};
  const int sametag[5] = {-1, 3, -1, 4, -1};
  const double xi[3] = {0.2, 0.1, 0.0};
  EXPECT_EQ(closest_image(xi, x, 1, sametag), 3);
  const double near_last[3] = {9.0, 9.0, 0.0};
  EXPECT_EQ(closest_image(near_last, x, 1, sametag), 4);
  // a single image is itself; of equal distances the first in the chain
  EXPECT_EQ(closest_image(xi, x, 2, sametag), 2);
  const double middle[3] = {4.5, 0.0, 0.0};
  EXPECT_EQ(closest_image(middle, x, 1, sametag), 1);
  // at a scale of 1e8 the same choice
  const double big[5][3] = {
      {0, 0, 0}, {9.5e8, 0, 0}, {5e8, 5e8, 5e8}, {-0.5e8, 0, 0}, {9.5e8, 1e9, 0}};
  const double *xb[5] = {big[0], big[1], big[2], big[3], big[4]};
  const double xib[3] = {0.2e8, 0.1e8, 0.0};
  EXPECT_EQ(closest_image(xib, xb, 1, sametag), 3);
}

TEST(MeshGeometry, VertexNormalsOfAllRowsNameTheSmallestAtomMissingAVertex)
{
  // rows 0..3: IDs 40, 30, 20, 10; row 2 is no mesh vertex; rows 0 and 1 form a right triangle
  // with the vertex of ID 50 (not found from row 0) and ID 60 (found nowhere)
  Storage<int> s(4);
  const int tag[4] = {40, 30, 20, 10};
  const double rows[4][3] = {{0, 0, 0}, {1, 0, 0}, {9, 9, 9}, {0, 1, 0}};
  const double *x[4] = {rows[0], rows[1], rows[2], rows[3]};
  s.mesh[0] = s.mesh[1] = s.mesh[3] = 1;
  s.ntri[0] = 2;    // (40, 30, 10) and (40, 50, 30)
  s.tri[0][0][0] = 30;
  s.tri[0][0][1] = 10;
  s.tri[0][1][0] = 50;
  s.tri[0][1][1] = 30;
  s.ntri[1] = 1;    // (30, 10, 40)
  s.tri[1][0][0] = 10;
  s.tri[1][0][1] = 40;
  s.ntri[3] = 1;    // (10, 40, 60)
  s.tri[3][0][0] = 40;
  s.tri[3][0][1] = 60;
  auto position = [&](int, int id) -> const double * {
    for (int j = 0; j < 4; j++)
      if (tag[j] == id) return x[j];
    return nullptr;
  };
  double nrows[4][3];
  double *n[4] = {nrows[0], nrows[1], nrows[2], nrows[3]};
  for (auto &r : nrows) r[0] = r[1] = r[2] = 7.0;
  const auto bad = vertex_normals(s.arrays(), 4, tag, x, position, n);
  EXPECT_EQ(bad.first, 10);
  EXPECT_EQ(bad.second, 60);
  expect_vector(n[0], 0.0, 0.0, 1.0, 0.0);    // the triangle with 50 adds nothing
  expect_vector(n[1], 0.0, 0.0, 1.0, 0.0);
  expect_vector(n[2], 0.0, 0.0, 0.0, 0.0);
  expect_vector(n[3], 0.0, 0.0, 0.0, 0.0);

  // with every vertex found, no row is named
  s.tri[3][0][1] = 30;
  s.tri[0][1][0] = 10;
  const auto none = vertex_normals(s.arrays(), 4, tag, x, position, n);
  EXPECT_EQ(none.first, 0);
  EXPECT_EQ(none.second, 0);
}

TEST(MeshGeometry, FitToBoxWrapsClampsOrRefuses)
{
  const bool shrink[2] = {false, false}, fixed_upper[2] = {false, true};
  int side = -1;
  double c = 0.5;
  EXPECT_EQ(fit_to_box(c, 0.0, 1.0, false, fixed_upper, side), BoxFit::kInside);
  EXPECT_EQ(c, 0.5);
  EXPECT_EQ(side, -1);
  // periodic: what the wrap left outside by round-off goes to lo
  c = 1.0;
  EXPECT_EQ(fit_to_box(c, 0.0, 1.0, true, shrink, side), BoxFit::kInside);
  EXPECT_EQ(c, 0.0);
  c = -1e-17;
  EXPECT_EQ(fit_to_box(c, 0.0, 1.0, true, shrink, side), BoxFit::kInside);
  EXPECT_EQ(c, 0.0);
  // shrink-wrapped: onto the face, the upper one excluded
  c = -2.0;
  EXPECT_EQ(fit_to_box(c, -1.0, 3.0, false, shrink, side), BoxFit::kGrows);
  EXPECT_EQ(c, -1.0);
  EXPECT_EQ(side, 0);
  c = 3.0;
  EXPECT_EQ(fit_to_box(c, -1.0, 3.0, false, shrink, side), BoxFit::kGrows);
  EXPECT_EQ(c, std::nextafter(3.0, -1.0));
  EXPECT_LT(c, 3.0);
  EXPECT_EQ(side, 1);
  // a fixed face refuses and leaves the value; the other face of the same direction clamps
  c = 1e9;
  EXPECT_EQ(fit_to_box(c, 0.0, 1.0, false, fixed_upper, side), BoxFit::kOutside);
  EXPECT_EQ(c, 1e9);
  EXPECT_EQ(side, 1);
  c = -1e-9;
  EXPECT_EQ(fit_to_box(c, 0.0, 1.0, false, fixed_upper, side), BoxFit::kGrows);
  EXPECT_EQ(c, 0.0);
  EXPECT_EQ(side, 0);
}
