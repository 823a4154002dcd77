// Lagged smooth friction of Incremental Potential Contact (Li, Ferguson, Schneider, Langlois,
// Zorin, Panozzo, Jiang, Kaufman 2020, "Incremental Potential Contact", section 5 and
// supplement) for the barrier pairs of barrier.h (issue 15: "lagged smooth friction with
// coefficient mu").
//
// Lagged data of a pair (built once per step at the step's start positions x^n, then constant):
// - the signed closest-point weights w_i of its vertices: the closest points are c_A = sum of
//   w_i x_i over the first primitive (w_i >= 0, summing to 1) and c_B likewise over the second,
//   with the second's weights stored negated, so that sum_i w_i x_i = c_A - c_B and sum_i w_i = 0
//   (a rigid translation of the pair has no relative displacement). The closest features are
//   those of distance.h's classification (face, edge or vertex of a triangle; interiors or end
//   points of two edges), so the data agree with the barrier's distance;
// - the unit normal n = (c_A - c_B) / |c_A - c_B| and an orthonormal tangent basis T (3 x 2,
//   T^T T = I, T^T n = 0) of the plane normal to it;
// - the normal force magnitude lambda = kappa e |b'(g)|, g = d - dmin: minus the derivative of
//   the pair's barrier energy kappa e b(d - dmin) in the distance d, the mollifier e (distance.h)
//   held at its value at x^n (e = 1 except for edge-edge pairs whose edges are nearly parallel;
//   those hand their contact to the point-triangle pairs of their ends, and so their friction
//   too, instead of counting it twice). Since |dd/dx_i| = |w_i| (the closest points are
//   stationary), the barrier's force on vertex i is lambda w_i n: lambda is the force that
//   pushes the two sides apart. Zero for a pair beyond dmin + dhat.
//
// Friction energy of the step for the displacement u = x - x^n of the pair's vertices:
//   u_T = T^T sum_i w_i u_i  (2-vector: the tangential relative displacement of the closest
//   points), y = |u_T|,  D(u) = mu lambda f0(y),
// with, for the slip length eps = eps_v h (eps_v a velocity, h the step; below eps the friction
// is static-like, above it is Coulomb's mu lambda):
//   f1(y) = 2 y / eps - y^2 / eps^2          for 0 <= y < eps,   1 for y >= eps,
//   f0(y) = -y^3 / (3 eps^2) + y^2 / eps + eps / 3   for 0 <= y < eps,   y for y >= eps,
// f0' = f1, f0(0) = eps / 3, f0(eps) = eps (the constant eps / 3 makes f0 continuous; it adds
// nothing to the force). Smoothness: f1(eps) = 1 and f1'(eps) = 2 / eps - 2 eps / eps^2 = 0,
// so f1 is C1 and f0 is C2 at y = eps: only f0''' jumps (from -2 / eps^2 to 0). At y = 0,
// f0(|u_T|) = eps / 3 + |u_T|^2 / eps - |u_T|^3 / (3 eps^2) is C2 in u_T (|u_T|^3 is), its
// Hessian there (2 / eps) I. So D is C2 in x everywhere; its third derivatives jump where
// y = 0 and y = eps.
//
// Gradient: dD/du_i = mu lambda w_i (f1(y) / y) T u_T  (f1(y) / y -> 2 / eps as y -> 0), so the
// friction force on the first side, sum of -dD/du_i over its vertices, is
// -mu lambda f1(y) T u_T / y: against the tangential relative motion, of magnitude mu lambda
// beyond eps and 2 mu lambda y / eps for y << eps. Its sum over all vertices is 0.
// Hessian: d2D/du_i du_j = mu lambda w_i w_j T M T^T with the 2 x 2
//   M = (f1(y) / y) (I - q q^T) + f1'(y) q q^T,  q = u_T / y   ((2 / eps) I at y = 0),
// IPC's form f1/y I + (f1' y - f1) / y^3 u_T u_T^T written by its eigenvalues: f1(y) / y >= 0
// across the motion, f1'(y) >= 0 along it (0 beyond eps). Both are >= 0 for this f1, so the
// exact Hessian is already positive semi-definite and IPC's projection (clamping the 2 x 2's
// eigenvalues at 0) changes nothing: it is done anyway, by clamping f1' at 0 against round-off.
// The Hessian has rank <= 2; the lagged data have no derivatives (they are constants of the
// step), so these are the exact derivatives of the lagged potential.
//
// Use in the glue (fix nosb/contact, a later phase):
// - Under fix sissm (implicit): at the start of each step, from the positions x^n, build a
//   FrictionPair for every pair within dmin + dhat (the barrier's active pairs; the candidates are
//   those of the barrier, and only pairs with lambda > 0 need be kept). Keep them, with x^n of
//   their vertices (owned and ghost), for the whole step; do not rebuild them at the iterates.
//   At every iterate x add D(x - x^n) to the step's energy, its gradient to the residual (as
//   force densities, gradient / vfrac, like the barrier) and its Hessian blocks to the matrix
//   where the barrier's go. eps = eps_v h with fix sissm's step h, eps_v a keyword of the fix
//   (a speed well below the sliding speeds of the scene). A neighbor list rebuild inside a step
//   must not drop the step's lagged pairs. One set of lagged data per step (IPC also allows
//   re-solving a step with data lagged at its own result; not needed for the incline below).
// - Under fix nve (explicit), recommended: build the pairs at the current positions at every
//   step (lambda = the barrier force now, nothing to lag) and use u = v dt, v the velocity at
//   the force evaluation (fix nve's half-step velocity). The force is then
//   -mu lambda s(|v_T| / eps_v) v_T / |v_T|, s(r) = 2 r - r^2 below 1, 1 beyond: Coulomb
//   friction regularised below the slip speed eps_v, independent of dt (eps = eps_v dt). Its
//   static regime is a damper of 2 mu lambda / eps_v per unit relative tangential speed, so an
//   explicit step needs dt < m eps_v / (mu lambda) for a vertex of mass m (the damper's
//   stability bound; half of it so that the slip does not reverse within a step): eps_v large
//   enough for that, or a small step. No guarantee of sticking.
// - Incline test (issue 15's acceptance): a block (or a vertex) resting on a fixed plane tilted
//   by theta under gravity g. Once its normal motion has settled, lambda sums to m g cos(theta)
//   over the pairs; it slides with acceleration g (sin(theta) - mu cos(theta)) when
//   mu < tan(theta), measured from the downslope velocity at two times well after the start
//   ((v2 - v1) / (t2 - t1), velocities from x^{n+1} - x^n), within 2%; for mu > tan(theta) it
//   creeps at the constant speed y / h with f1(y) = tan(theta) / mu, below eps_v (a sticking
//   block, up to the regularisation). unittest/core/contact/test_friction.cpp runs this with one
//   vertex over one triangle and a Newton solve of the implicit Euler step; the LAMMPS test
//   should do the same with a read_mesh block on an inclined held mesh.
//
// Coordinates are ordered as the arguments of the pair's builder, three per vertex, in a
// 12-vector; pairs of 2 (point-point) vertices leave the rest zero and
// ignore it. LAMMPS-free.

#ifndef PERISISSM_CONTACT_FRICTION_H
#define PERISISSM_CONTACT_FRICTION_H

#include "contact/barrier.h"

#include <array>

namespace PeriSISSM {

// ---- the scalar mollifier of the slip (eps = eps_v h > 0, y >= 0) ----

// f0(y), f1(y) = f0'(y), f1'(y) and f1(y) / y. Inputs: y >= 0 the tangential slip (length);
// eps > 0 the slip length. Outputs: as above; f1(y) / y at y = 0 is its limit 2 / eps,
// f1'(eps) = 0 (the left and right limits agree).
double friction_f0(double y, double eps);
double friction_f1(double y, double eps);
double friction_f1_derivative(double y, double eps);
double friction_f1_over_y(double y, double eps);

// ---- lagged data of a pair ----

// Parameters of friction: mu the coefficient, slip_length eps = eps_v h (length, > 0).
struct FrictionParameters {
  double mu = 0.0;
  double slip_length = 1.0;
};

// The lagged data of one pair at x^n (see the top of this file).
struct FrictionPair {
  int count = 0;                // vertices: 4 (point-triangle, edge-edge), 2 (point-point)
  std::array<double, 4> w{};    // signed weights: sum w_i x_i = c_A - c_B, sum w_i = 0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();                      // unit, from c_B to c_A
  Eigen::Matrix<double, 3, 2> T = Eigen::Matrix<double, 3, 2>::Zero();    // tangent basis
  double lambda = 0.0;    // normal force magnitude kappa e |b'(d - dmin)|
};

// Builders from the pair's positions at x^n and the barrier's parameters. Inputs: the pair's
// points as for the barrier (p; t0 t1 t2), (a0 a1; b0 b1) with the mollifier threshold eps of
// edge_edge_mollifier_threshold(), (p; q). Outputs: the pair's lagged data; lambda
// = 0 beyond dmin + dhat, +inf for a gap <= 0 (never reached where the barrier holds).
// The first primitive (p, or edge a) is the side with weights >= 0. For a point over a face
// and for two edges' interiors the normal is the triangle's normal or the edges' cross
// product (turned towards the first side), which is the closest-point direction without its
// cancellation at small d; otherwise the closest-point direction, and when the closest points
// coincide (d = 0), the triangle's normal, the edges' cross product or, failing those, e_z.
FrictionPair point_triangle_friction_pair(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                          const Eigen::Vector3d &t1, const Eigen::Vector3d &t2,
                                          const BarrierParameters &prm);
FrictionPair edge_edge_friction_pair(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                     const Eigen::Vector3d &b0, const Eigen::Vector3d &b1,
                                     double eps, const BarrierParameters &prm);
FrictionPair point_point_friction_pair(const Eigen::Vector3d &p, const Eigen::Vector3d &q,
                                       const BarrierParameters &prm);

// An orthonormal basis (3 x 2) of the plane normal to a unit vector n, right-handed with n
// (t0 x t1 = n). Inputs: n, |n| = 1. Output: T.
Eigen::Matrix<double, 3, 2> tangent_basis(const Eigen::Vector3d &n);

// ---- the friction potential of a pair ----

// u_T = T^T sum_i w_i u_i. Inputs: pair; u the displacement x - x^n (12, ordered as the
// builder's arguments). Output: the tangential relative displacement (2).
Eigen::Vector2d tangential_displacement(const FrictionPair &pair, const Vector12d &u);

// D = mu lambda f0(|u_T|), its gradient (12; the force is minus it) and its Hessian (12 x 12,
// positive semi-definite). Inputs: pair (lagged at x^n); u = x - x^n (or v dt explicitly);
// prm. Outputs: as above, zero in the slots beyond pair.count.
double friction_energy(const FrictionPair &pair, const Vector12d &u, const FrictionParameters &prm);
Vector12d friction_gradient(const FrictionPair &pair, const Vector12d &u,
                            const FrictionParameters &prm);
Matrix12d friction_hessian(const FrictionPair &pair, const Vector12d &u,
                           const FrictionParameters &prm);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_FRICTION_H
