// 3x3 solves and rotations. Symmetric 3x3 matrices are double[6]: xx yy zz xy xz yz; general
// ones row-major double[9].

#ifndef PERISISSM_LINALG_SMALL_MATRIX_H
#define PERISISSM_LINALG_SMALL_MATRIX_H

namespace PeriSISSM {

// Solve the symmetric positive definite system D d = r (cofactors).
void solve_spd3(const double D[6], const double r[3], double d[3]);

// Solve the general system M x = r by cofactors; false (x untouched) when |det M| <= tiny.
bool solve3(const double M[9], const double r[3], double tiny, double x[3]);

// w = u x v
inline void cross3(const double *u, const double *v, double *w)
{
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}

// Rotate r in place about the unit axis k by the angle with cosine cs and sine sn (Rodrigues).
void rotate3(const double k[3], double cs, double sn, double r[3]);

}    // namespace PeriSISSM

#endif    // PERISISSM_LINALG_SMALL_MATRIX_H
