// A flat triangulated sheet for the membrane tests (test_curvature.cpp, test_plate_bending.cpp,
// test_hinge.cpp).

#ifndef PERISISSM_TEST_FLAT_SHEET_H
#define PERISISSM_TEST_FLAT_SHEET_H

#include <array>
#include <random>
#include <vector>

namespace {

// The triangles of a grid of NX x NY cells whose vertex (i, j) is j (NX + 1) + i: squares cut
// along alternating diagonals (tools/make_sheet.py's default pattern). Output: tri (appended).
void alternate_triangles(int NX, int NY, std::vector<std::array<int, 3>> &tri)
{
  const int nx = NX + 1;
  for (int j = 0; j < NY; j++)
    for (int i = 0; i < NX; i++) {
      const int p00 = j * nx + i, p10 = p00 + 1, p01 = p00 + nx, p11 = p01 + 1;
      if ((i + j) % 2 == 0) {
        tri.push_back({p00, p10, p11});
        tri.push_back({p00, p11, p01});
      } else {
        tri.push_back({p00, p10, p01});
        tri.push_back({p10, p11, p01});
      }
    }
}

// A flat grid of NX x NY cells of size h in the plane z = 0, squares cut along alternating
// diagonals, interior vertices moved by up to jitter h (boundary ones stay).
struct Sheet {
  int nx, ny;
  std::vector<double> X;
  std::vector<std::array<int, 3>> tri;
  double area = 0.0;

  Sheet(int NX, int NY, double h, double jitter, unsigned seed = 7) : nx(NX + 1), ny(NY + 1)
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        const bool inner = i > 0 && j > 0 && i < nx - 1 && j < ny - 1;
        const double dx = inner ? jitter * u(rng) : 0.0, dy = inner ? jitter * u(rng) : 0.0;
        X.insert(X.end(), {h * (i + dx - 0.5 * NX), h * (j + dy - 0.5 * NY), 0.0});
      }
    alternate_triangles(NX, NY, tri);
    area = NX * NY * h * h;
  }
  int nv() const { return nx * ny; }
};

}    // namespace

#endif    // PERISISSM_TEST_FLAT_SHEET_H
