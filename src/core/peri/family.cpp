// Bond families (see family.h).

#include "peri/family.h"

#include "membrane/membrane.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

namespace {
  using RowMatrix3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
}    // namespace

// K is symmetric PSD by construction (sum of w V xi xi^T). The singularity test uses its
// eigenvalues from the closed-form 3x3 solver (accurate to ~1e-8 relative to lambda_max,
// ample for the ratio test against kMinShapeConditioning = 0.05: a family confined to a
// plane or a line gives ~1e-16). The inverse itself is the cofactor formula, accurate to
// round-off times the condition number (the eigen-decomposition would be only as accurate as
// the closed-form eigenvectors, which are poor for the nearly isotropic K of interior
// particles).
bool invert_shape_tensor(const double K[9], double lambda_ref, double Kinv[9], double *lambda_max)
{
  Eigen::Map<RowMatrix3d> out(Kinv);
  out.setZero();
  if (lambda_max) *lambda_max = 0.0;
  const RowMatrix3d k = Eigen::Map<const RowMatrix3d>(K);
  if (!k.allFinite()) return false;
  const Eigen::Matrix3d ks = 0.5 * (k + k.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(ks, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d lam = eig.eigenvalues();    // ascending
  if (lambda_max) *lambda_max = lam(2);
  const double ref = std::max(lam(2), lambda_ref);
  if (!(lam(2) > 0.0) || !(lam(0) >= kMinShapeConditioning * ref)) return false;
  const Eigen::Matrix3d inv = ks.inverse();
  if (!inv.allFinite()) return false;
  out = 0.5 * (inv + inv.transpose());
  return true;
}

void ReferenceBox::face_distances(double width[3]) const
{
  const double xprd = box[0], yprd = box[1], zprd = box[2];
  const double yz = box[3], xz = box[4], xy = box[5];
  const double bxc = std::sqrt(yprd * zprd * yprd * zprd + xy * zprd * xy * zprd +
                               (xy * yz - yprd * xz) * (xy * yz - yprd * xz));
  width[0] = xprd * yprd * zprd / bxc;
  width[1] = yprd * zprd / std::sqrt(zprd * zprd + yz * yz);
  width[2] = zprd;
}

bool bonds_leave_group(const Families &fam, int nlocal, const int *mask, int groupbit)
{
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const int *jl = fam.jlocal[i];
    for (int b = 0; b < fam.npartner[i]; b++)
      if (jl[b] >= 0 && !(mask[jl[b]] & groupbit)) return true;
  }
  return false;
}

double partial_volume_factor(double r, double delta, double h)
{
  const double half = 0.5 * h;
  if (r <= delta - half) return 1.0;
  if (r > delta + half) return 0.0;
  return (delta + half - r) / h;
}

double bond_weight(double r, double delta, double vi, double vj, double ti, double tj)
{
  const double hi = ti > 0.0 ? std::sqrt(vi / ti) : std::cbrt(vi);
  const double hj = tj > 0.0 ? std::sqrt(vj / tj) : std::cbrt(vj);
  const double h = 0.5 * (hi + hj);
  return partial_volume_factor(r, delta, h) * vj;
}

void update_shape(const Families &fam, const double *x0, const ReferenceBox &box, int i,
                  const double *n0)
{
  double K[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const int *jl = fam.jlocal[i];
  const double *om = fam.omega[i];
  for (int b = 0; b < fam.npartner[i]; b++) {
    if (jl[b] < 0) continue;
    double xi[3];
    reference_bond(x0, box, i, jl[b], xi);
    if (n0) {
      const double along = xi[0] * n0[0] + xi[1] * n0[1] + xi[2] * n0[2];
      for (int k = 0; k < 3; k++) xi[k] -= along * n0[k];
    }
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) K[3 * r + c] += om[b] * xi[r] * xi[c];
  }
  double lmax;
  const bool regular = n0 ? invert_membrane_shape_tensor(K, n0, fam.lamref[i], fam.kinv[i], &lmax)
                          : invert_shape_tensor(K, fam.lamref[i], fam.kinv[i], &lmax);
  fam.kregular[i] = regular ? 1 : 0;
  fam.lamref[i] = std::max(fam.lamref[i], lmax);
}

}    // namespace PeriSISSM
