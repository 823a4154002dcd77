// The bending term of a membrane (doc/theory.rst, "Bending"): the discrete-shells hinge energy
// of Grinspun et al. (2003) over the interior edges of a triangle mesh,
//   E = sum_e c_e (theta_e - theta0_e)^2,    c_e = D |e0|^2 / (2 A0_e),
// theta_e the signed dihedral angle of the two triangles at edge e (atan2 of the normals' sine
// and cosine: rotation invariant, defined for every fold short of a degenerate triangle),
// theta0_e its rest value (curved rest shapes), |e0| the rest length of the edge, A0_e the rest
// area of the two triangles together and D the bending modulus (energy). The factor 1/2 is the
// calibration: on a mesh of equilateral triangles bent into a cylinder of curvature kappa (any
// direction of the axis), the sum over the edges of |e|^2 theta^2 / A_e is kappa^2 per unit area
// (measured: 1.994 .. 2.002 kappa^2 / 2 on a 120 x 120 patch, the rest is its boundary), so E is
// the plate's D kappa^2 / 2 per unit area (Kirchhoff plate, cylindrical bending). A mesh of right
// triangles (squares cut along alternating diagonals) gives the same along its grid lines and
// 1.5 times as much for bending about a diagonal: the hinge energy is only as isotropic as the
// mesh.
//
// A hinge is four vertices: x0, x1 the edge, x2 the third vertex of the triangle (x0, x1, x2)
// and x3 that of (x1, x0, x3), both triangles in the mesh's orientation. LAMMPS-free.

#ifndef PERISISSM_MEMBRANE_HINGE_H
#define PERISISSM_MEMBRANE_HINGE_H

namespace PeriSISSM {

// Signed dihedral angle of a hinge and its gradient.
// Inputs:  x0..x3 (3 doubles each). Outputs: returns theta in (-pi, pi], 0 when flat, positive
//          when the triangles fold away from their normals (a ridge seen from the side the
//          normals point to); when grad is not null, grad[v][k] =
//          d theta / d x_v,k. A degenerate triangle (zero area) gives theta = 0 and a zero
//          gradient.
double hinge_angle(const double *x0, const double *x1, const double *x2, const double *x3,
                   double grad[4][3] = nullptr);

// Energy of one hinge and its derivatives.
// Inputs:  x0..x3; theta0 rest angle; c = D |e0|^2 / (2 A0) (hinge_stiffness()).
// Outputs: returns c (theta - theta0)^2 (energy); force[v] = -dE/dx_v (when not null); block[v]
//          (when not null) the Gauss-Newton diagonal blocks 2 c g_v g_v^T (xx yy zz xy xz yz),
//          symmetric positive semi-definite (the term's own Hessian is not).
double hinge_energy(const double *x0, const double *x1, const double *x2, const double *x3,
                    double theta0, double c, double force[4][3] = nullptr,
                    double block[4][6] = nullptr);

// c_e = D |e0|^2 / (2 A0) of a hinge from its rest positions (A0 the two triangles' area).
double hinge_stiffness(double D, const double *x0, const double *x1, const double *x2,
                       const double *x3);

}    // namespace PeriSISSM

#endif    // PERISISSM_MEMBRANE_HINGE_H
