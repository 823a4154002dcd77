// The contact barrier of Incremental Potential Contact (Li, Ferguson, Schneider, Langlois, Zorin,
// Panozzo, Jiang, Kaufman 2020, "Incremental Potential Contact", eq. 6 and supplement) with the
// thickness of Codimensional IPC (Li, Kaufman, Jiang 2021): for a pair of primitives at distance d
// the gap is g = d - dmin (dmin >= 0 the thickness, the separation the contact keeps) and
//
//   b(g) = -(g - dhat)^2 ln(g / dhat)   for 0 < g < dhat,   0 for g >= dhat,
//
// which is C2 at g = dhat (b = b' = b'' = 0 there) and grows without bound as g -> 0. The pair's
// energy is kappa b(g) (kappa the barrier stiffness, energy / length^2), times the edge-edge
// mollifier for edge-edge pairs (distance.h).
//
// Choice (issue 15 leaves it open): the barrier is a function of the distance d itself, not of d^2
// as in IPC, so that dhat and dmin are lengths and "acts within dhat beyond dmin" holds literally
// (doc/fix_nosb_contact.rst). Since the distances come squared (D = d^2, distance.h), the chain
// rule through d = sqrt(D) is applied once, in distance_barrier_*():
//   B(D) = b(sqrt(D) - dmin),  B' = b' / (2 d),  B'' = b'' / (4 D) - b' / (4 d^3),
// safe because the barrier only acts for d > dmin >= 0 (and b -> inf as d -> dmin).
//
// The pair energies' Hessians are optionally projected to positive semi-definite (eigenvalues
// clamped at 0), for the Newton-Krylov matrix. LAMMPS-free.

#ifndef PERISISSM_CONTACT_BARRIER_H
#define PERISISSM_CONTACT_BARRIER_H

#include "contact/distance.h"

namespace PeriSISSM {

// ---- the scalar barrier of the gap g ----

// b(g), b'(g), b''(g). Inputs: g gap (length), dhat > 0 its range. Outputs: 0 for g >= dhat;
// for g <= 0 (never reached under a CCD-limited step) +inf, -inf, +inf.
double barrier(double g, double dhat);
double barrier_first_derivative(double g, double dhat);
double barrier_second_derivative(double g, double dhat);

// ---- the barrier of a squared distance with a thickness ----

// B(D) = b(sqrt(D) - dmin) and its derivatives in D. Inputs: D squared distance; dmin >= 0
// thickness; dhat > 0. Outputs: 0 for sqrt(D) >= dmin + dhat; +inf (B) when sqrt(D) <= dmin.
double distance_barrier(double D, double dmin, double dhat);
double distance_barrier_first_derivative(double D, double dmin, double dhat);
double distance_barrier_second_derivative(double D, double dmin, double dhat);

// ---- pair energies ----

// Parameters of the barrier: kappa (energy / length^2), dhat and dmin (lengths).
struct BarrierParameters {
  double kappa = 1.0;
  double dhat = 1.0;
  double dmin = 0.0;
};

// kappa B(D(x)) of a point-triangle pair (p, t0, t1, t2), its gradient (12) and Hessian
// (12 x 12, projected to PSD when project_psd). Zero when the pair is beyond dmin + dhat.
// Requires a gap > 0 where it acts.
double point_triangle_barrier_energy(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                     const Eigen::Vector3d &t1, const Eigen::Vector3d &t2,
                                     const BarrierParameters &prm);
Vector12d point_triangle_barrier_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                          const Eigen::Vector3d &t1, const Eigen::Vector3d &t2,
                                          const BarrierParameters &prm);
Matrix12d point_triangle_barrier_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                         const Eigen::Vector3d &t1, const Eigen::Vector3d &t2,
                                         const BarrierParameters &prm, bool project_psd);

// kappa e(x) B(D(x)) of an edge-edge pair (a0, a1, b0, b1), e the mollifier with threshold eps
// (edge_edge_mollifier_threshold() of the rest shape), its gradient and Hessian.
double edge_edge_barrier_energy(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, double eps,
                                const BarrierParameters &prm);
Vector12d edge_edge_barrier_gradient(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                     const Eigen::Vector3d &b0, const Eigen::Vector3d &b1,
                                     double eps, const BarrierParameters &prm);
Matrix12d edge_edge_barrier_hessian(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                    const Eigen::Vector3d &b0, const Eigen::Vector3d &b1,
                                    double eps, const BarrierParameters &prm, bool project_psd);

// kappa B(|p - q|^2) of two particles (volumetric types: dmin their separation), gradient (6)
// and Hessian (6 x 6).
double point_point_barrier_energy(const Eigen::Vector3d &p, const Eigen::Vector3d &q,
                                  const BarrierParameters &prm);
Vector6d point_point_barrier_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &q,
                                      const BarrierParameters &prm);
Matrix6d point_point_barrier_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &q,
                                     const BarrierParameters &prm, bool project_psd);

// The energy (returned) and gradient (g) of the three functions above together, from the
// squared distance D known to the caller, the edge-edge mollifier computed once: the form for
// force evaluations.
// D: the pair's squared distance as point_triangle_distance2() etc. give it.
double point_triangle_barrier(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                              const Eigen::Vector3d &t1, const Eigen::Vector3d &t2, double D,
                              const BarrierParameters &prm, Vector12d &g);
double edge_edge_barrier(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                         const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, double eps,
                         double D, const BarrierParameters &prm, Vector12d &g);
double point_point_barrier(const Eigen::Vector3d &p, const Eigen::Vector3d &q, double D,
                           const BarrierParameters &prm, Vector6d &g);

// The nearest positive semi-definite matrix (Frobenius norm) of a symmetric one: its
// eigen-decomposition with negative eigenvalues set to 0.
Matrix12d project_to_psd(const Matrix12d &H);
Matrix6d project_to_psd(const Matrix6d &H);

// ---- barrier stiffness (IPC supplement, "Adaptive barrier stiffness") ----

// Initial kappa, in the units of IPC's incremental potential, whose inertia term has the mass
// matrix as its Hessian (a force-balance residual r = rho (yhat - y) + c f is that potential's
// gradient scaled by -1/c per unit volume, so the force-based stiffness is this kappa / c, c = h^2
// for backward Euler). Inputs: bbox_diagonal (length) of the scene; dhat; average_mass of the
// nodes; energy_dot_barrier = grad E . grad B and barrier_dot_barrier = grad B . grad B, the dot
// products (summed over all ranks by the caller) of the gradient of the incremental potential
// without the barrier, E, and of the barrier sum at kappa = 1, B. Outputs: kappa =
// -(grad E . grad B) / |grad B|^2 clamped to [kappa_min, kappa_max], kappa_max = 100 kappa_min,
// where kappa_min makes the barrier's normal stiffness kappa b''(g0) at the gap
// g0 = min(1e-8 bbox_diagonal, dhat / 2) equal to 1e11 average_mass (IPC's choice: a ratio of
// two Hessians of the incremental potential, free of units). kappa_max is returned through the
// reference.
double initial_barrier_stiffness(double bbox_diagonal, double dhat, double average_mass,
                                 double energy_dot_barrier, double barrier_dot_barrier,
                                 double &kappa_max);

// IPC's update between Newton iterations: kappa doubles (up to kappa_max) while the smallest gap
// of all pairs is below 1e-9 bbox_diagonal and still shrinking. Inputs: the smallest gaps of the
// previous and current iterate; kappa_max; kappa; bbox_diagonal. Output: the new kappa.
double update_barrier_stiffness(double previous_min_gap, double min_gap, double kappa_max,
                                double kappa, double bbox_diagonal);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_BARRIER_H
