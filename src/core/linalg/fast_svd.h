// Fast signed singular value decomposition of a 3x3 matrix: the one the force evaluation uses.
//
// PERI-SISSM mechanics core (LAMMPS-free). Same contract as signed_svd() (signed_svd.h), which
// stays the reference the tests compare against.

#ifndef PERISISSM_FAST_SVD_H
#define PERISISSM_FAST_SVD_H

#include "linalg/signed_svd.h"

namespace PeriSISSM {

// Signed SVD of a 3x3 matrix by one-sided Jacobi rotations of the columns of F and a Givens QR
// of F V (McAdams et al., "Computing the singular value decomposition of 3x3 matrices with minimal branching and
// elementary floating point operations", Univ. Wisconsin TR1690, 2011; here in double precision
// with exact rotation angles and a convergence test instead of a fixed number of sweeps).
//
// Inputs:
//   F  3x3 matrix, any rank, any sign of det F.
// Outputs (returned), as signed_svd():
//   U, V  rotations (det = +1, orthonormal to round-off);
//   s     |s_1| >= |s_2| >= |s_3|, s_1, s_2 >= 0, s_3 < 0 when det F < 0, never -0;
//   F = U diag(s) V^T to a few eps |F|. Non-finite F gives s = NaN, U = V = I.
// U and V may differ from signed_svd()'s where singular values repeat (they are not unique
// there); s, and every isotropic function U diag(g(s)) V^T, agree to round-off.
SignedSVD fast_signed_svd(const Eigen::Matrix3d &F);

// Two at once: a = fast_signed_svd(Fa), b = fast_signed_svd(Fb) to the last bit, in about the
// time of one and a half (the Jacobi rotations of one matrix are a chain of dependent square
// roots and divisions; the two chains run side by side).
void fast_signed_svd(const Eigen::Matrix3d &Fa, const Eigen::Matrix3d &Fb, SignedSVD &a,
                     SignedSVD &b);

// Four at once: out[l] = fast_signed_svd(F[l]) to the last bit, one matrix per lane of 4-wide
// registers where the build has the x86-64-v3 code (-DPERISISSM_CPU_DISPATCH=ON, the default
// with GCC or Clang on x86-64) and the processor runs it (x86_64_v3(), fused.h), otherwise as
// two pairs. Rotated small strains, the common case of a force evaluation, measured once with
// tools/bench_passes.sh on a 2-core x86-64 guest: 185 ns a matrix, 330 in pairs, 475 alone.
void fast_signed_svd(const Eigen::Matrix3d F[4], SignedSVD out[4]);

}    // namespace PeriSISSM

#endif    // PERISISSM_FAST_SVD_H
