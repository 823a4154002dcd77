// The correspondence of a membrane particle (doc/theory.rst, "Membranes"): a particle of a
// triangle mesh (a 2-manifold in 3D) whose family lies in its tangent plane.
//
// Reference: the particle's unit normal n0 (from the mesh) and the tangent plane T0 = I - n0 n0^T.
// Its shape tensor is the in-plane one, K = sum_j omega (T0 xi) (x) (T0 xi) (rank 2), and K^+ its
// pseudo-inverse in the plane (K^+ n0 = 0). The in-plane gradient A = M K^+ (M = sum_j omega eta
// (x) xi, as for a volume; K^+ xi = K^+ T0 xi) maps the tangent plane into space, A n0 = 0. The
// current normal is the unit normal of A's image, n = A t1 x A t2 / |A t1 x A t2| ((t1, t2, n0) a
// right-handed frame), and the deformation gradient is completed through the thickness,
//   F = A + s3 n (x) n0,
// so that n0 is a right singular vector of F with singular value s3 (the thickness stretch) and
// the in-plane singular values are those of A. Plane stress: s3 is chosen so that the stress
// through the thickness vanishes, Phat_3(s1, s2, s3) = 0 (Material::plane_stress_stretch). The
// energy density is W(s1, s2, s3), and since dW/ds3 = 0 and n . dn = 0 (n is a unit vector),
// dW = P : dA exactly: the force state is w P K^+ xi, the same bond force as a volume's with K^-1
// replaced by K^+. The normal n comes from the particle's own bonds, so forces need neither the
// mesh's triangles nor its current normals. A membrane therefore resists stretching and shear in
// its plane and nothing else; bending is a separate term.
//
// LAMMPS-free. 3x3 matrices are row-major double[9]; symmetric ones double[6] xx yy zz xy xz yz.

#ifndef PERISISSM_MEMBRANE_MEMBRANE_H
#define PERISISSM_MEMBRANE_MEMBRANE_H

namespace PeriSISSM {

class Material;

// A right-handed orthonormal frame (t1, t2, n0) of a unit normal n0, a fixed function of n0.
// Inputs: n0 unit vector. Outputs: t1, t2 unit, t1 . n0 = t2 . n0 = t1 . t2 = 0, t1 x t2 = n0.
void tangent_frame(const double n0[3], double t1[3], double t2[3]);

// The in-plane shape tensor's pseudo-inverse with the singularity test of invert_shape_tensor()
// in two dimensions (family.h: kMinShapeConditioning).
// Inputs:  K (row-major 3x3, symmetric, K n0 = 0: built from projected bonds T0 xi); n0 unit
//          reference normal; lambda_ref >= 0 reference eigenvalue (0 = none).
// Outputs: Kinv = K^+ restricted to the tangent plane (symmetric, Kinv n0 = 0) when regular,
//          else zeros; lambda_max (if not null) the larger in-plane eigenvalue.
//          Returns true when regular: finite, lambda_max > 0 and lambda_min >= kMinShapeConditioning
//          * max(lambda_max, lambda_ref) for the two in-plane eigenvalues.
bool invert_membrane_shape_tensor(const double K[9], const double n0[3], double lambda_ref,
                                  double Kinv[9], double *lambda_max = nullptr);

// The membrane counterpart of correspondence_state() (particle.h).
// Inputs:  material; M (row-major, sum_j omega eta (x) xi); Kinv (the in-plane K^+ above); n0.
// Outputs: F (row-major, F = A + s3 n (x) n0 with plane stress), A (row-major force-state matrix
//          P K^+, so the particle's force state on a bond is omega A xi); when H is not null the
//          implicit stiffness kappa U diag(c1, c2, 0) U^T (kappa = tr(K^+) / 2; the thickness
//          direction, which carries no stress, gets none). Returns W(s1, s2, s3).
// A family collapsed to a line or a point has no image normal; n is then taken perpendicular to
// the image in the plane nearest to n0, and F stays finite.
double membrane_state(const Material &material, const double M[9], const double Kinv[9],
                      const double n0[3], double F[9], double A[9], double H[6] = nullptr);

// Stabilization modulus of a membrane particle: the volumetric rule (stabilization.h) in the
// plane, C = 4.8 Cs K kappa with kappa = tr(K^+) / 2, so C stays in the same proportion to the
// particle's correspondence stiffness as in a volume.
double membrane_stabilization_modulus(double Cs, double K, const double Kinv[9]);

}    // namespace PeriSISSM

#endif    // PERISISSM_MEMBRANE_MEMBRANE_H
