// A bending energy of a flat triangle mesh that is the Kirchhoff plate's on any triangulation
// (examples/membranes/README.md, "Choosing a bending energy"): per triangle T the mid-edge shape
// operator
//   k_T = 1/A_T sum_i |e_i| (d_i - g_T . t_i) t_i t_i^T,
// g_T the slope of the piecewise linear field on T, t_i the outward in-plane unit normal of its
// edge i, d_i the slope across edge i at its midpoint: the mean over the edge's one or two
// triangles of the slope there of the quadratic fitted to each triangle's stencil (its three
// vertices and the far vertices of the triangles across its edges; least squares over its
// vertices' 1-rings where an edge is on the boundary). Exact for quadratic fields (each fit
// is), and sum_T A_T k_T depends only on the boundary values (d_i is one value per edge,
// shared by both triangles, and cancels). For the sheet in 3D the coefficients apply to the
// positions y: three vectors Q_xx, Q_xy, Q_yy per triangle (zero on any rigid motion of the flat
// rest shape), and
//   E_T = A_T D/2 [|Q_xx + Q_yy|^2 - 2 (1 - nu) (Q_xx . Q_yy - |Q_xy|^2)],
// the plate energy D/2 [(tr k)^2 - 2 (1 - nu) det k] per area for bending without stretching
// (whose second derivatives of y are normal to the sheet). E is quadratic in y: its Hessian is
// constant and positive semi-definite (|nu| <= 1). LAMMPS-free.

#ifndef PERISISSM_MEMBRANE_CURVATURE_H
#define PERISISSM_MEMBRANE_CURVATURE_H

#include <array>
#include <cstdint>
#include <vector>

namespace PeriSISSM {

// The coefficients of one triangle: Q_c = sum_k coef[3 k + c] y_{vertex[k]}, c = xx, xy, yy
// (they sum to zero: evaluated as sum_k coef[3 k + c] (y_{vertex[k]} - y_{vertex[0]}))
// (in an orthonormal frame of the rest plane; E does not depend on which).
struct CurvatureStencil {
  std::vector<int> vertex;
  std::vector<double> coef;    // 3 per vertex (1 / length^2)
  double area = 0.0;           // A_T at rest
};

// What one triangle's stencil needs of the mesh around it, by vertex ID (any numbering): the
// triangles at a vertex and the rest positions. A distributed mesh answers for the vertices it
// holds (membrane/plate_bending.h); a whole mesh for all.
class CurvatureMesh {
 public:
  virtual ~CurvatureMesh() = default;
  // Outputs: others (replaced) = the triangles at vertex v as their other two corners (a, b),
  // (v, a, b) in the triangle's orientation. Returns false when v's triangles are not known.
  virtual bool triangles_at(std::int64_t v, std::vector<std::array<std::int64_t, 2>> &others)
      const = 0;
  // Outputs: d = X_to - X_from at rest (3 doubles; the minimum image in a periodic box).
  // Returns false when either vertex is not known.
  virtual bool rest_offset(std::int64_t from, std::int64_t to, double d[3]) const = 0;
};

// The stencil of one triangle by vertex IDs: its three corners first (in the order given), then
// the other vertices by increasing ID, so that every process that holds the triangle's
// neighbourhood builds the same coefficients in the same order.
struct TriangleStencil {
  std::vector<std::int64_t> vertex;
  std::vector<double> coef;    // 3 per vertex, as CurvatureStencil's
  double area = 0.0;
};

// How far from flat a stencil's rest shape may be: the rest positions are projected on the
// triangle's plane (the energy's rest state is flat), so a sheet roughened by a small random
// displacement or round-off is taken as the flat sheet it approximates, while a mesh curved at
// rest (a slope of 1% over the stencil: a radius of curvature under about 100 edges) is refused.
constexpr double kFlatTolerance = 1e-2;

enum class StencilStatus {
  ok,
  missing,       // a vertex (or its triangles) that the stencil needs is not known
  not_flat,      // a rest position of the stencil is off the triangle's plane by more than
                 //   kFlatTolerance of its distance (or of the triangle's mean edge)
  degenerate,    // a triangle of zero area, or a fit with fewer than six points off every conic
};

// Inputs: mesh; t the triangle's corners (IDs, in its orientation). Outputs: s (replaced; left
// empty unless ok). The fits use the rest positions projected on the triangle's plane.
StencilStatus triangle_stencil(const CurvatureMesh &mesh, const std::array<std::int64_t, 3> &t,
                               TriangleStencil &s);

// Inputs: nv vertices X (3 per vertex, flat around each triangle), tri (0-based, any
// orientation). Outputs: stencils, one per triangle, in tri's order (vertex = indices into X).
// Returns false (stencils cleared) when a triangle_stencil() is not ok.
bool build_curvature_stencils(int nv, const double *X, const std::vector<std::array<int, 3>> &tri,
                              std::vector<CurvatureStencil> &stencils);

// E_T at positions y (3 per vertex, indexed as the mesh). Outputs: when force is not null,
// force[3 k + d] = -dE_T / dy_{vertex[k], d} (3 per stencil vertex).
double curvature_energy(const CurvatureStencil &s, const double *y, double D, double nu,
                        double *force = nullptr);

// The parts of curvature_energy, for a pass that keeps each triangle's weights: adw (row-major
// 3x3) = A_T D W (W as in curvature_hessian); then, for m vertices (rows vertex, coefficients
// coef as CurvatureStencil's) at positions y, S (row-major 3x3, row c = dE/dQ_c) and the return
// value E_T; and the force on stencil vertex k, F = -sum_c coef[3 k + c] S_c.
void curvature_weights(double area, double D, double nu, double adw[9]);
double curvature_stress(const int *vertex, const double *coef, int m, const double adw[9],
                        const double *y, double S[9]);
inline void curvature_force(const double *coef_k, const double S[9], double F[3])
{
  for (int d = 0; d < 3; d++) {
    double g = 0.0;
    for (int c = 0; c < 3; c++) g += coef_k[c] * S[3 * c + d];
    F[d] = -g;
  }
}

// The constant Hessian of E_T: block (k, l) = h[m k + l] I (3x3), m = vertex.size(),
//   h[m k + l] = A_T D sum_cd W_cd coef[3 k + c] coef[3 l + d],
// W = [[1, 0, nu], [0, 2 (1 - nu), 0], [nu, 0, 1]] over (xx, xy, yy). Output h (resized).
void curvature_hessian(const CurvatureStencil &s, double D, double nu, std::vector<double> &h);

// One entry of that Hessian over A_T D: sum_cd W_cd coef[3 k + c] coef[3 l + d] (the diagonal
// blocks of an implicit pass need only k = l).
double curvature_form(const CurvatureStencil &s, int k, int l, double nu);

// The Hessian as a Gram matrix: Output a (3 doubles) = sqrt(A_T D) L^T coef_k, W = L L^T (its
// Cholesky factor), so that a_k . a_l = h[m k + l] (the coarse level's factors,
// peri/bond_stiffness.h PlateCouplings).
void curvature_factor(const CurvatureStencil &s, int k, double D, double nu, double a[3]);

}    // namespace PeriSISSM

#endif    // PERISISSM_MEMBRANE_CURVATURE_H
