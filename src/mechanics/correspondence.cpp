// Correspondence peridynamics helpers (see correspondence.h).

#include "correspondence.h"

#include "material.h"
#include "signed_svd.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

namespace {
using RowMatrix3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using ConstMap = Eigen::Map<const RowMatrix3d>;
using Map = Eigen::Map<RowMatrix3d>;
}  // namespace

// K is symmetric PSD by construction (sum of w V xi xi^T). The singularity test uses its
// eigenvalues from the closed-form 3x3 solver (accurate to ~1e-8 relative to lambda_max,
// ample for the ratio test against kMinShapeConditioning = 0.05: a family confined to a
// plane or a line gives ~1e-16). The inverse itself is the cofactor formula, accurate to
// round-off times the condition number (the eigen-decomposition would be only as accurate as
// the closed-form eigenvectors, which are poor for the nearly isotropic K of interior
// particles).
bool invert_shape_tensor(const double K[9], double lambda_ref, double Kinv[9],
                         double *lambda_max)
{
  Map out(Kinv);
  out.setZero();
  if (lambda_max) *lambda_max = 0.0;
  const RowMatrix3d k = ConstMap(K);
  if (!k.allFinite()) return false;
  const Eigen::Matrix3d ks = 0.5 * (k + k.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(ks, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d lam = eig.eigenvalues();  // ascending
  if (lambda_max) *lambda_max = lam(2);
  const double ref = std::max(lam(2), lambda_ref);
  if (!(lam(2) > 0.0) || !(lam(0) >= kMinShapeConditioning * ref)) return false;
  const Eigen::Matrix3d inv = ks.inverse();
  if (!inv.allFinite()) return false;
  out = 0.5 * (inv + inv.transpose());
  return true;
}

double partial_volume_factor(double r, double delta, double h)
{
  const double half = 0.5 * h;
  if (r <= delta - half) return 1.0;
  if (r > delta + half) return 0.0;
  return (delta + half - r) / h;
}

// Cs 18K/(pi delta^5) * kappa_i / kappa_0 with kappa = tr(K^-1)/3 and kappa_0 = 15/(4 pi delta^5):
// the delta^5 and pi cancel, 18 * 4 / 15 / 3 = 8/5.
double stabilization_modulus(double Cs, double K, const double Kinv[9])
{
  return 1.6 * Cs * K * (Kinv[0] + Kinv[4] + Kinv[8]);
}

namespace {

// F = M K^-1, P = U diag(Phat) V^T from one signed SVD, A = P K^-1, and when H is given
// H = kappa U diag(c) U^T with kappa = tr(K^-1)/3; returns W(F).
double particle_state(const Material& material, const double M[9], const double Kinv[9],
                      double F[9], double A[9], double* H)
{
  const RowMatrix3d kinv = ConstMap(Kinv);
  const Eigen::Matrix3d f = ConstMap(M) * kinv;
  const SignedSVD svd = signed_svd(f);
  const Eigen::Vector3d phat = material.principal_stress(svd.s);
  const Eigen::Matrix3d P = svd.U * phat.asDiagonal() * svd.V.transpose();
  Map fout(F), aout(A);
  fout = f;
  aout = P * kinv;
  if (H) {
    const double kappa = (Kinv[0] + Kinv[4] + Kinv[8]) / 3.0;
    const Eigen::Vector3d c = material.implicit_coefficient(svd.s);
    const Eigen::Matrix3d h = kappa * svd.U * c.asDiagonal() * svd.U.transpose();
    H[0] = h(0, 0);
    H[1] = h(1, 1);
    H[2] = h(2, 2);
    H[3] = h(0, 1);
    H[4] = h(0, 2);
    H[5] = h(1, 2);
  }
  return material.energy(svd.s);
}

}  // namespace

double correspondence_state(const Material& material, const double M[9], const double Kinv[9],
                            double F[9], double A[9])
{
  return particle_state(material, M, Kinv, F, A, nullptr);
}

double correspondence_state(const Material& material, const double M[9], const double Kinv[9],
                            double F[9], double A[9], double H[6])
{
  return particle_state(material, M, Kinv, F, A, H);
}

// tau = P F^T = U diag(Phat) V^T V diag(s) U^T = U diag(Phat .* s) U^T.
double cauchy_stress(const Material& material, const double F[9], double sigma[6], double& J)
{
  const Eigen::Matrix3d f = ConstMap(F);
  const SignedSVD svd = signed_svd(f);
  const Eigen::Vector3d phat = material.principal_stress(svd.s);
  J = svd.s.prod();
  const Eigen::Matrix3d tau = svd.U * phat.cwiseProduct(svd.s).asDiagonal() * svd.U.transpose();
  const double scale = 1.0 / std::max(J, kCauchyMinJ);
  sigma[0] = scale * tau(0, 0);
  sigma[1] = scale * tau(1, 1);
  sigma[2] = scale * tau(2, 2);
  sigma[3] = scale * 0.5 * (tau(0, 1) + tau(1, 0));
  sigma[4] = scale * 0.5 * (tau(0, 2) + tau(2, 0));
  sigma[5] = scale * 0.5 * (tau(1, 2) + tau(2, 1));
  return material.energy(svd.s);
}

double von_mises(const double s[6])
{
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

}  // namespace PeriSISSM
