// Momentum balance of a free group (see momentum.h).

#include "solvers/momentum.h"

#include "linalg/exact_sum.h"
#include "linalg/small_matrix.h"

#include <cmath>

namespace PeriSISSM {

void balance_momentum(const Rows &rows, Reductions &red, const MomentumBalance &step, double **x,
                      double **yn, double **yhat, double **fext, double **moment)
{
  const double h = step.h, cf = step.c;
  const bool euler = step.euler;
  constexpr int NM = kMomentumColumns;
  const int nlocal = rows.n;
  const double *rho = rows.density;
  const double *vfrac = rows.volume;
  const int lagged = fext == nullptr;
  double *t = (nlocal > 0) ? moment[0] : nullptr;

  // mass and centre of mass c^n of the step's start
  double s[NM];
  // (rows outside the group are zeros: their y^n is not set, and 0 times a NaN left in memory is
  // a NaN that would reach the sums)
  for (int i = 0; i < nlocal; i++) {
    double *row = moment[i];
    for (int k = 0; k < 4; k++) row[k] = 0.0;
    if (!rows.has(i)) continue;
    const double m = rho[i] * vfrac[i];
    row[0] = m;
    for (int k = 0; k < 3; k++) row[1 + k] = m * yn[i][k];
  }
  exact_sums(t, nlocal, NM, 4, red, s);
  const double mass = s[0];
  if (!(mass > 0.0)) return;
  const double cn[3] = {s[1] / mass, s[2] / mass, s[3] / mass};

  // the step's displacement of the centre, the targets h P^{n+1} - h^2 F and L^n, and F
  for (int i = 0; i < nlocal; i++) {
    double *row = moment[i];
    for (int k = 0; k < 12; k++) row[k] = 0.0;
    if (!rows.has(i)) continue;
    const double m = rho[i] * vfrac[i];
    double q[3], mv[3];
    for (int k = 0; k < 3; k++) {
      q[k] = yn[i][k] - cn[k];
      mv[k] = m * (yhat[i][k] - yn[i][k]) / h;    // m v^n (+ the lagged force, see above)
      row[k] = m * (x[i][k] - yn[i][k]);
      row[3 + k] = mv[k];
      row[6 + k] = lagged ? 0.0 : vfrac[i] * fext[i][k];
    }
    cross3(q, mv, row + 9);
  }
  exact_sums(t, nlocal, NM, 12, red, s);
  double dcen[3], d[3], Ln[3];
  for (int k = 0; k < 3; k++) {
    dcen[k] = s[k] / mass;    // c - c^n
    // move of the centre: the target sum m (y - y^n) (euler: h P^{n+1}; else
    // sum m (yhat - y^n) + c F) minus where the solve left it
    const double target = euler ? h * (s[3 + k] + h * s[6 + k]) : h * s[3 + k] + cf * s[6 + k];
    d[k] = (target - s[k]) / mass;
    Ln[k] = euler ? s[9 + k] : 0.0;
  }

  // rotation about the centre c = c^n + dcen: r_i = y_i - c, kept in the last three columns
  for (int i = 0; i < nlocal; i++)
    if (rows.has(i))
      for (int k = 0; k < 3; k++)
        moment[i][12 + k] = (x[i][k] - yn[i][k]) - dcen[k] + (yn[i][k] - cn[k]);
  for (int iter = 0; iter < 8; iter++) {
    for (int i = 0; i < nlocal; i++) {
      double *row = moment[i];
      for (int k = 0; k < 12; k++) row[k] = 0.0;
      if (!rows.has(i)) continue;
      const double m = rho[i] * vfrac[i];
      const double *r = row + 12;
      const double q[3] = {yn[i][0] - cn[0], yn[i][1] - cn[1], yn[i][2] - cn[2]};
      double fe[3] = {0.0, 0.0, 0.0};
      if (!lagged)
        for (int k = 0; k < 3; k++) fe[k] = vfrac[i] * fext[i][k];
      if (!euler) {
        // G = sum r x b, b = m (yhat - c^n) + c V fext; J = sum (r b^T - (r . b) I)
        double b[3];
        for (int k = 0; k < 3; k++) b[k] = m * ((yhat[i][k] - yn[i][k]) + q[k]) + cf * fe[k];
        cross3(r, b, row);
        const double rb = r[0] * b[0] + r[1] * b[1] + r[2] * b[2];
        for (int a = 0; a < 3; a++)
          for (int c = 0; c < 3; c++) row[3 + 3 * a + c] = r[a] * b[c] - (a == c ? rb : 0.0);
        continue;
      }
      double w[3], u[3];
      cross3(q, r, w);
      cross3(r, fe, u);
      for (int k = 0; k < 3; k++) row[k] = m * w[k] / h - h * u[k];    // G + L^n
      const double qr = q[0] * r[0] + q[1] * r[1] + q[2] * r[2];
      const double rf = r[0] * fe[0] + r[1] * fe[1] + r[2] * fe[2];
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
          row[3 + 3 * a + c] = m / h * ((a == c ? qr : 0.0) - r[a] * q[c]) -
              h * (r[a] * fe[c] - (a == c ? rf : 0.0));
    }
    exact_sums(t, nlocal, NM, 12, red, s);
    const double G[3] = {Ln[0] - s[0], Ln[1] - s[1], Ln[2] - s[2]};    // -G
    // (a group on a line or at a point has no inertia about some axis: no rotation then)
    const double jtrace = fabs(s[3]) + fabs(s[7]) + fabs(s[11]);
    double dtheta[3];
    if (!solve3(s + 3, G, 1.0e-12 * jtrace * jtrace * jtrace, dtheta)) break;
    const double angle =
        sqrt(dtheta[0] * dtheta[0] + dtheta[1] * dtheta[1] + dtheta[2] * dtheta[2]);
    if (!(angle > 0.0)) break;
    const double k[3] = {dtheta[0] / angle, dtheta[1] / angle, dtheta[2] / angle};
    const double cs = cos(angle), sn = sin(angle);
    for (int i = 0; i < nlocal; i++)
      if (rows.has(i)) rotate3(k, cs, sn, moment[i] + 12);
    if (angle < 1.0e-15) break;
  }

  // y <- c + d + R r, written as a displacement of y (no large coordinates subtracted)
  for (int i = 0; i < nlocal; i++) {
    if (!rows.has(i)) continue;
    const double *r = moment[i] + 12;
    for (int k = 0; k < 3; k++) {
      const double r0 = (x[i][k] - yn[i][k]) - dcen[k] + (yn[i][k] - cn[k]);
      x[i][k] += d[k] + (r[k] - r0);
    }
  }
}

}    // namespace PeriSISSM
