// 3x3 solves and rotations (see small_matrix.h).

#include "linalg/small_matrix.h"

#include <cmath>

namespace PeriSISSM {

void solve_spd3(const double D[6], const double r[3], double d[3])
{
  const double a = D[0], b = D[1], c = D[2], xy = D[3], xz = D[4], yz = D[5];
  const double c00 = b * c - yz * yz, c01 = xz * yz - xy * c, c02 = xy * yz - xz * b;
  const double c11 = a * c - xz * xz, c12 = xy * xz - a * yz, c22 = a * b - xy * xy;
  const double inv = 1.0 / (a * c00 + xy * c01 + xz * c02);
  d[0] = inv * (c00 * r[0] + c01 * r[1] + c02 * r[2]);
  d[1] = inv * (c01 * r[0] + c11 * r[1] + c12 * r[2]);
  d[2] = inv * (c02 * r[0] + c12 * r[1] + c22 * r[2]);
}

bool solve3(const double M[9], const double r[3], double tiny, double x[3])
{
  const double c00 = M[4] * M[8] - M[5] * M[7], c01 = M[5] * M[6] - M[3] * M[8],
               c02 = M[3] * M[7] - M[4] * M[6];
  const double det = M[0] * c00 + M[1] * c01 + M[2] * c02;
  if (!(std::fabs(det) > tiny)) return false;
  const double c10 = M[2] * M[7] - M[1] * M[8], c11 = M[0] * M[8] - M[2] * M[6],
               c12 = M[1] * M[6] - M[0] * M[7];
  const double c20 = M[1] * M[5] - M[2] * M[4], c21 = M[2] * M[3] - M[0] * M[5],
               c22 = M[0] * M[4] - M[1] * M[3];
  x[0] = (c00 * r[0] + c10 * r[1] + c20 * r[2]) / det;
  x[1] = (c01 * r[0] + c11 * r[1] + c21 * r[2]) / det;
  x[2] = (c02 * r[0] + c12 * r[1] + c22 * r[2]) / det;
  return true;
}

void rotate3(const double k[3], double cs, double sn, double r[3])
{
  double kr[3];
  cross3(k, r, kr);
  const double kdr = k[0] * r[0] + k[1] * r[1] + k[2] * r[2];
  for (int c = 0; c < 3; c++) r[c] = r[c] * cs + kr[c] * sn + k[c] * kdr * (1.0 - cs);
}

}    // namespace PeriSISSM
