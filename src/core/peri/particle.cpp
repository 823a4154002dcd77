// The correspondence of one particle (see particle.h).

#include "peri/particle.h"

#include "linalg/fast_svd.h"
#include "materials/material.h"

#include <algorithm>
#include <cmath>

namespace PeriSISSM {

namespace {
  using RowMatrix3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  using ConstMap = Eigen::Map<const RowMatrix3d>;
  using Map = Eigen::Map<RowMatrix3d>;
}    // namespace

void particle_stress(const Material &material, const Eigen::Matrix3d &F, ParticleStress &out,
                     bool with_split)
{
  stress_from_svd(material, fast_signed_svd(F), out, with_split);
}

void stress_from_svd(const Material &material, const SignedSVD &svd, ParticleStress &out,
                     bool with_split)
{
  // (P is formed in a local and then stored: Eigen's vectorized 3x3 products may sum in another
  // order when they write straight into a member, and every force must have the same bits
  // wherever the pipeline is called from)
  const Eigen::Vector3d phat = material.principal_stress(svd.s);
  const Eigen::Matrix3d P = svd.U * phat.asDiagonal() * svd.V.transpose();
  out.svd = svd;
  out.phat = phat;
  out.P = P;
  out.c = with_split ? material.implicit_coefficient(out.svd.s) : Eigen::Vector3d::Zero();
  out.W = material.energy(out.svd.s);
}

Eigen::Matrix3d first_piola(const Material &material, const Eigen::Matrix3d &F)
{
  ParticleStress ps;
  particle_stress(material, F, ps);
  return ps.P;
}

Eigen::Matrix3d implicit_part(const ParticleStress &ps)
{
  return ps.svd.U * ps.c.cwiseProduct(ps.svd.s).asDiagonal() * ps.svd.V.transpose();
}

Eigen::Matrix3d implicit_direction(const ParticleStress &ps)
{
  const Eigen::Matrix3d D = ps.svd.U * ps.c.asDiagonal() * ps.svd.U.transpose();
  return 0.5 * (D + D.transpose());
}

void implicit_stiffness(const ParticleStress &ps, double kappa, double H[6])
{
  const Eigen::Matrix3d h = kappa * ps.svd.U * ps.c.asDiagonal() * ps.svd.U.transpose();
  H[0] = h(0, 0);
  H[1] = h(1, 1);
  H[2] = h(2, 2);
  H[3] = h(0, 1);
  H[4] = h(0, 2);
  H[5] = h(1, 2);
}

namespace {

  // F = M K^-1
  Eigen::Matrix3d gradient(const double M[9], const double Kinv[9])
  {
    const RowMatrix3d kinv = ConstMap(Kinv);
    return ConstMap(M) * kinv;
  }

  // the outputs of correspondence_state() from F and its SVD
  double finish_state(const Material &material, const Eigen::Matrix3d &f, const SignedSVD &svd,
                      const double Kinv[9], double F[9], double A[9], double H[6])
  {
    ParticleStress ps;
    stress_from_svd(material, svd, ps, H != nullptr);
    const RowMatrix3d kinv = ConstMap(Kinv);
    Map fout(F), aout(A);
    fout = f;
    aout = ps.P * kinv;
    if (H) implicit_stiffness(ps, (Kinv[0] + Kinv[4] + Kinv[8]) / 3.0, H);
    return ps.W;
  }

}    // namespace

double correspondence_state(const Material &material, const double M[9], const double Kinv[9],
                            double F[9], double A[9], double H[6])
{
  const Eigen::Matrix3d f = gradient(M, Kinv);
  return finish_state(material, f, fast_signed_svd(f), Kinv, F, A, H);
}

void correspondence_states(const CorrespondenceState &a, const CorrespondenceState &b)
{
  const Eigen::Matrix3d fa = gradient(a.M, a.Kinv), fb = gradient(b.M, b.Kinv);
  SignedSVD sa, sb;
  fast_signed_svd(fa, fb, sa, sb);
  *a.W = finish_state(*a.material, fa, sa, a.Kinv, a.F, a.A, a.H);
  *b.W = finish_state(*b.material, fb, sb, b.Kinv, b.F, b.A, b.H);
}

void correspondence_states(const CorrespondenceState (&s)[4])
{
  Eigen::Matrix3d f[4];
  SignedSVD svd[4];
  for (int l = 0; l < 4; l++) f[l] = gradient(s[l].M, s[l].Kinv);
  fast_signed_svd(f, svd);
  for (int l = 0; l < 4; l++)
    *s[l].W = finish_state(*s[l].material, f[l], svd[l], s[l].Kinv, s[l].F, s[l].A, s[l].H);
}

// tau = P F^T = U diag(phat) V^T V diag(s) U^T = U diag(phat .* s) U^T.
double cauchy_stress(const Material &material, const double F[9], double sigma[6], double &J)
{
  ParticleStress ps;
  particle_stress(material, ConstMap(F), ps);
  J = ps.svd.s.prod();
  const Eigen::Matrix3d &U = ps.svd.U;
  const Eigen::Matrix3d tau = U * ps.phat.cwiseProduct(ps.svd.s).asDiagonal() * U.transpose();
  const double scale = 1.0 / std::max(J, kCauchyMinJ);
  sigma[0] = scale * tau(0, 0);
  sigma[1] = scale * tau(1, 1);
  sigma[2] = scale * tau(2, 2);
  sigma[3] = scale * 0.5 * (tau(0, 1) + tau(1, 0));
  sigma[4] = scale * 0.5 * (tau(0, 2) + tau(2, 0));
  sigma[5] = scale * 0.5 * (tau(1, 2) + tau(2, 1));
  return ps.W;
}

double von_mises(const double s[6])
{
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

void nosb_atom_row(const Material &material, bool regular, const double F[9], double w,
                   double damage, double dtstable, double row[NosbAtom::NCOLUMNS])
{
  using namespace NosbAtom;
  for (int k = 0; k < NCOLUMNS; k++) row[k] = 0.0;
  row[JACOBIAN] = 1.0;
  row[DAMAGE] = damage;
  row[DTSTABLE] = dtstable;
  if (!regular) return;
  row[ENERGY] = w;
  cauchy_stress(material, F, &row[SXX], row[JACOBIAN]);
  row[VONMISES] = von_mises(&row[SXX]);
}

}    // namespace PeriSISSM
