// Signed singular value decomposition of a 3x3 deformation gradient.

#include "linalg/signed_svd.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <limits>

namespace PeriSISSM {

// Method: two-sided Jacobi SVD (Eigen::JacobiSVD, no QR preconditioner: F is square). It scales
// F by its largest entry before iterating, accumulates U and V as products of plane rotations
// (so they are orthonormal to round-off even for repeated or zero singular values), and returns
// sigma_1 >= sigma_2 >= sigma_3 >= 0. F = 0 gives sigma = 0, U = V = I.
//
// Sign fix-up: if det U0 = -1, flip the last column of U0 and negate sigma_3; likewise for V0.
// Each flip keeps U diag(s) V^T unchanged (u_3 sigma_3 v_3^T -> (-u_3)(-sigma_3) v_3^T). After
// both, det U = det V = +1 and s_3 < 0 exactly when det U0 det V0 = -1, which for a nonsingular
// F is sign(det F) = det U0 det V0. Only the smallest singular value ever changes sign, which is
// the inversion convention of Irving et al. 2004.
SignedSVD signed_svd(const Eigen::Matrix3d &F)
{
  SignedSVD out;
  if (!F.allFinite()) {
    out.U.setIdentity();
    out.V.setIdentity();
    out.s.setConstant(std::numeric_limits<double>::quiet_NaN());
    return out;
  }
  // GCC 12 warns that JacobiSVD's singular values "may be used uninitialized": they are not set
  // on its non-finite-input path, which the check above excludes. False positive, silenced here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
  const Eigen::JacobiSVD<Eigen::Matrix3d, Eigen::NoQRPreconditioner> svd(
      F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  out.U = svd.matrixU();
  out.V = svd.matrixV();
  out.s = svd.singularValues();
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
  if (out.U.determinant() < 0.0) {
    out.U.col(2) = -out.U.col(2);
    out.s(2) = -out.s(2);
  }
  if (out.V.determinant() < 0.0) {
    out.V.col(2) = -out.V.col(2);
    out.s(2) = -out.s(2);
  }
  if (out.s(2) == 0.0) out.s(2) = 0.0;    // no -0: "s_3 < 0" means inverted, not singular
  return out;
}

}    // namespace PeriSISSM
