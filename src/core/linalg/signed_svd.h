// Signed singular value decomposition of a 3x3 deformation gradient.
//
// PERI-SISSM mechanics core (LAMMPS-free). See doc/design doc/theory.rst and
// Irving, Teran, Fedkiw 2004 (invertible finite elements) for the sign convention.

#ifndef PERISISSM_SIGNED_SVD_H
#define PERISISSM_SIGNED_SVD_H

#include <Eigen/Core>

namespace PeriSISSM {

// F = U diag(s) V^T with U, V proper rotations (det = +1) and signed singular values s.
struct SignedSVD {
  Eigen::Matrix3d U;
  Eigen::Matrix3d V;
  Eigen::Vector3d s;
};

// Signed SVD of a 3x3 matrix.
//
// Inputs:
//   F  3x3 matrix (deformation gradient, dimensionless), any rank, any sign of det F.
// Outputs (returned):
//   U, V  3x3 rotations: orthonormal to round-off, det U = det V = +1.
//   s     signed singular values, |s_1| >= |s_2| >= |s_3|; s_1, s_2 >= 0; s_3 < 0 exactly when
//         the ordinary SVD of F has det(U_0) det(V_0) = -1, i.e. when det F < 0 (for det F = 0
//         s_3 = +0). F = U diag(s) V^T to round-off (relative to |F|).
//   A non-finite entry in F gives s = (NaN, NaN, NaN) and U = V = I (callers check).
SignedSVD signed_svd(const Eigen::Matrix3d &F);

}    // namespace PeriSISSM

#endif    // PERISISSM_SIGNED_SVD_H
