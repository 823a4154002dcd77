/* PERI-SISSM core: geometry of triangle meshes (see mesh_geometry.h). */
#include "mesh/mesh_geometry.h"

#include "linalg/constants.h"

#include <cmath>

namespace PeriSISSM {

namespace {

  void cross(const double a[3], const double b[3], double c[3])
  {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
  }

  double dot(const double a[3], const double b[3])
  {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }

}    // namespace

// Rodrigues' formula: R v = v cos(theta) + (u x v) sin(theta) + u (u . v)(1 - cos(theta))
void place(const Placement &p, const double X[3], double x[3])
{
  double v[3] = {p.scale * X[0], p.scale * X[1], p.scale * X[2]};
  if (p.theta != 0.0) {
    const double len = std::sqrt(dot(p.axis, p.axis));
    const double u[3] = {p.axis[0] / len, p.axis[1] / len, p.axis[2] / len};
    const double angle = p.theta * kPi / 180.0;
    const double c = std::cos(angle), s = std::sin(angle);
    double uxv[3];
    cross(u, v, uxv);
    const double uv = dot(u, v);
    for (int k = 0; k < 3; k++) x[k] = v[k] * c + uxv[k] * s + u[k] * uv * (1.0 - c);
    for (int k = 0; k < 3; k++) v[k] = x[k];
  }
  for (int k = 0; k < 3; k++) x[k] = v[k] + p.offset[k];
}

BoxFit fit_to_box(double &c, double lo, double hi, bool periodic, const bool fixed[2], int &side)
{
  if (periodic) {
    if (c < lo || c >= hi) c = lo;
    return BoxFit::kInside;
  }
  const int beyond = (c < lo) ? 0 : (c >= hi) ? 1 : -1;
  if (beyond < 0) return BoxFit::kInside;
  side = beyond;
  if (fixed[side]) return BoxFit::kOutside;
  c = side ? std::nextafter(hi, lo) : lo;
  return BoxFit::kGrows;
}

double triangle_area(const double a[3], const double b[3], const double c[3])
{
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double n[3];
  cross(e1, e2, n);
  return 0.5 * std::sqrt(dot(n, n));
}

std::vector<double> vertex_areas(const std::vector<std::array<double, 3>> &vertices,
                                 const std::vector<std::array<int, 3>> &triangles)
{
  std::vector<double> area(vertices.size(), 0.0);
  for (const auto &t : triangles) {
    const double third =
        triangle_area(vertices[t[0]].data(), vertices[t[1]].data(), vertices[t[2]].data()) / 3.0;
    for (int c = 0; c < 3; c++) area[t[c]] += third;
  }
  return area;
}

int closest_image(const double xi[3], const double *const *x, int j, const int *sametag)
{
  int closest = j;
  double rsqmin = 0.0;
  for (int d = 0; d < 3; d++) rsqmin += (x[j][d] - xi[d]) * (x[j][d] - xi[d]);
  for (int k = sametag[j]; k >= 0; k = sametag[k]) {
    double rsq = 0.0;
    for (int d = 0; d < 3; d++) rsq += (x[k][d] - xi[d]) * (x[k][d] - xi[d]);
    if (rsq < rsqmin) {
      rsqmin = rsq;
      closest = k;
    }
  }
  return closest;
}

void add_angle_weighted_normal(const double xi[3], const double xa[3], const double xb[3],
                               double n[3])
{
  const double e1[3] = {xa[0] - xi[0], xa[1] - xi[1], xa[2] - xi[2]};
  const double e2[3] = {xb[0] - xi[0], xb[1] - xi[1], xb[2] - xi[2]};
  double c[3];
  cross(e1, e2, c);
  const double len = std::sqrt(dot(c, c));
  if (!(len > 0.0)) return;
  const double angle = std::atan2(len, dot(e1, e2));
  for (int k = 0; k < 3; k++) n[k] += angle * c[k] / len;
}

bool normalize_or_zero(double n[3])
{
  const double len = std::sqrt(dot(n, n));
  if (!(len > 0.0)) {
    n[0] = n[1] = n[2] = 0.0;
    return false;
  }
  for (int k = 0; k < 3; k++) n[k] /= len;
  return true;
}

}    // namespace PeriSISSM
