// First Piola-Kirchhoff stress and per-particle quantities.

#include "stress.h"

namespace PeriSISSM {

// For isotropic W(F) = W(s(F)), dW/dF = sum_k dW/ds_k ds_k/dF and ds_k/dF = u_k v_k^T
// (valid for signed singular values too: s_3 = u_3^T F v_3 with the flipped columns).
// So P = sum_k Phat_k u_k v_k^T = U diag(Phat) V^T. At repeated singular values U, V are not
// unique but P is, since a symmetric W gives Phat_i = Phat_j when s_i = s_j.
Eigen::Matrix3d first_piola(const Material& material, const Eigen::Matrix3d& F)
{
  const SignedSVD svd = signed_svd(F);
  return svd.U * material.principal_stress(svd.s).asDiagonal() * svd.V.transpose();
}

// P^+ = U diag(c .* s) V^T. The stiffness direction D = U diag(c) U^T satisfies
// D F = U diag(c) U^T U diag(s) V^T = P^+, so with eta ~= F xi the implicit bond force is
// linear in eta (math.md section 2). D is symmetrized explicitly so that it is symmetric to
// the last bit; it is PSD because c >= 0.
void particle_stress(const Material& material, const Eigen::Matrix3d& F, ParticleStress& out)
{
  out.svd = signed_svd(F);
  const Eigen::Vector3d& s = out.svd.s;
  const Eigen::Matrix3d& U = out.svd.U;
  const Eigen::Matrix3d Vt = out.svd.V.transpose();
  const Eigen::Vector3d phat = material.principal_stress(s);
  const Eigen::Vector3d c = material.implicit_coefficient(s);
  out.J = s.prod();
  out.W = material.energy(s);
  out.P = U * phat.asDiagonal() * Vt;
  out.P_implicit = U * c.cwiseProduct(s).asDiagonal() * Vt;
  const Eigen::Matrix3d D = U * c.asDiagonal() * U.transpose();
  out.stiffness = 0.5 * (D + D.transpose());
}

}  // namespace PeriSISSM
