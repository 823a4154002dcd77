// The bending term of a membrane (see hinge.h).

#include "membrane/hinge.h"

#include "linalg/small_matrix.h"

#include <cmath>

namespace PeriSISSM {

namespace {

  inline double dot(const double a[3], const double b[3])
  {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }

  inline void sub(const double *a, const double *b, double c[3])
  {
    for (int k = 0; k < 3; k++) c[k] = a[k] - b[k];
  }

}    // namespace

// With e = x1 - x0, NA = e x (x2 - x0) and NB = (x3 - x0) x e (the two triangles' normals times
// twice their areas; equal directions when flat), theta = atan2((NA x NB) . e / |e|, NA . NB).
// Moving x2 along NA turns triangle A about the edge by |e| / |NA| per unit length, so
//   d theta / d x2 = -|e| NA / |NA|^2,   d theta / d x3 = -|e| NB / |NB|^2,
// and the edge's vertices take the rest so that the gradient is translation invariant:
//   d theta / d x0 = ((x1 - x2) . e) / |e| NA / |NA|^2 + ((x1 - x3) . e) / |e| NB / |NB|^2
//   ... (x0 <-> x1 with the opposite sign). (Bridson et al. 2003; Tamstorf and Grinspun 2013.)
double hinge_angle(const double *x0, const double *x1, const double *x2, const double *x3,
                   double grad[4][3])
{
  double e[3], a[3], b[3], na[3], nb[3], m[3];
  sub(x1, x0, e);
  sub(x2, x0, a);
  sub(x3, x0, b);
  cross3(e, a, na);
  cross3(b, e, nb);
  const double le = std::sqrt(dot(e, e));
  const double la2 = dot(na, na), lb2 = dot(nb, nb);
  if (grad)
    for (int v = 0; v < 4; v++) grad[v][0] = grad[v][1] = grad[v][2] = 0.0;
  if (!(le > 0.0) || !(la2 > 0.0) || !(lb2 > 0.0)) return 0.0;
  cross3(na, nb, m);
  const double theta = std::atan2(dot(m, e) / le, dot(na, nb));
  if (grad) {
    double d2[3], d3[3];
    sub(x1, x2, d2);
    sub(x1, x3, d3);
    const double s0a = dot(d2, e) / le, s0b = dot(d3, e) / le;
    sub(x2, x0, d2);
    sub(x3, x0, d3);
    const double s1a = dot(d2, e) / le, s1b = dot(d3, e) / le;
    for (int k = 0; k < 3; k++) {
      const double ua = na[k] / la2, ub = nb[k] / lb2;
      grad[2][k] = -le * ua;
      grad[3][k] = -le * ub;
      grad[0][k] = s0a * ua + s0b * ub;
      grad[1][k] = s1a * ua + s1b * ub;
    }
  }
  return theta;
}

double hinge_energy(const double *x0, const double *x1, const double *x2, const double *x3,
                    double theta0, double c, double force[4][3], double block[4][6])
{
  double g[4][3];
  const double theta = hinge_angle(x0, x1, x2, x3, g);
  double d = theta - theta0;
  // the angle difference on the circle (a rest angle near +-pi and a current one across it)
  if (d > M_PI)
    d -= 2.0 * M_PI;
  else if (d < -M_PI)
    d += 2.0 * M_PI;
  if (force)
    for (int v = 0; v < 4; v++)
      for (int k = 0; k < 3; k++) force[v][k] = -2.0 * c * d * g[v][k];
  if (block)
    for (int v = 0; v < 4; v++) {
      const double *u = g[v];
      double *out = block[v];
      out[0] = 2.0 * c * u[0] * u[0];
      out[1] = 2.0 * c * u[1] * u[1];
      out[2] = 2.0 * c * u[2] * u[2];
      out[3] = 2.0 * c * u[0] * u[1];
      out[4] = 2.0 * c * u[0] * u[2];
      out[5] = 2.0 * c * u[1] * u[2];
    }
  return c * d * d;
}

double hinge_stiffness(double D, const double *x0, const double *x1, const double *x2,
                       const double *x3)
{
  double e[3], a[3], b[3], na[3], nb[3];
  sub(x1, x0, e);
  sub(x2, x0, a);
  sub(x3, x0, b);
  cross3(e, a, na);
  cross3(b, e, nb);
  const double area = 0.5 * (std::sqrt(dot(na, na)) + std::sqrt(dot(nb, nb)));
  return area > 0.0 ? 0.5 * D * dot(e, e) / area : 0.0;
}

}    // namespace PeriSISSM
