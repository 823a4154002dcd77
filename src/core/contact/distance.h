// Distances between the primitives of barrier contact (issue 15; doc/fix_nosb_contact.rst): the
// squared distance of a point and a triangle and of two edges, with exact gradients and Hessians
// with respect to the 12 coordinates, as in Incremental Potential Contact (Li, Ferguson,
// Schneider, Langlois, Zorin, Panozzo, Jiang, Kaufman 2020, section 4 and supplement):
//
// - the closest features are classified first (the face, an edge or a vertex of the triangle;
//   the interiors of both edges, an end point and an edge, or two end points), and the squared
//   distance is then the smooth distance of those features: point-point |p - q|^2, point-line
//   |(e0 - p) x (e1 - p)|^2 / |e1 - e0|^2, point-plane ((p - t0) . n)^2 / |n|^2 with
//   n = (t1 - t0) x (t2 - t0), and line-line ((b0 - a0) . n)^2 / |n|^2 with
//   n = (a1 - a0) x (b1 - b0). Across a change of class the squared distance is C1 (the closest
//   points move continuously), not C2.
// - the edge-edge mollifier of IPC (section 4.3): for nearly parallel edges the line-line
//   distance is ill-conditioned and its closest points jump, so the edge-edge energy is
//   multiplied by e(c) = (2 - c / eps) c / eps for c < eps (1 beyond),
//   c = |(a1 - a0) x (b1 - b0)|^2 and eps = 1e-3 |A1 - A0|^2 |B1 - B0|^2 from the rest shape:
//   the product is C1 and vanishes for parallel edges (their contact is carried by the
//   point-triangle pairs of the edges' ends).
//
// Every smooth piece is built from two polynomials in the coordinates, the triple product
// s = det[a, b, c] and the squared cross product w = |b x c|^2, composed with a square and a
// quotient; their derivatives are written out below (distance.cpp) and tested against finite
// differences over scales 1e-6 .. 1e6 (unittest/core/contact/test_distance.cpp).
//
// Coordinates are ordered as the arguments: (p, t0, t1, t2) and (a0, a1, b0, b1), three per
// point. Degenerate primitives never give NaN: a triangle of zero area is treated as its three
// edges, an edge of zero length as its end point. LAMMPS-free.

#ifndef PERISISSM_CONTACT_DISTANCE_H
#define PERISISSM_CONTACT_DISTANCE_H

#include <Eigen/Core>

namespace PeriSISSM {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Vector9d = Eigen::Matrix<double, 9, 1>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

// ---- building blocks (smooth everywhere they are defined) ----

// |p - q|^2. Inputs: p, q points. Outputs: value; gradient 6 (p, q); Hessian 6 x 6.
double point_point_distance2(const Eigen::Vector3d &p, const Eigen::Vector3d &q);
Vector6d point_point_distance2_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &q);
Matrix6d point_point_distance2_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &q);

// Squared distance of p to the line through e0, e1: |(e0 - p) x (e1 - p)|^2 / |e1 - e0|^2.
// Inputs: p; e0 != e1. Outputs: value; gradient 9 (p, e0, e1); Hessian 9 x 9.
double point_line_distance2(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                            const Eigen::Vector3d &e1);
Vector9d point_line_distance2_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                                       const Eigen::Vector3d &e1);
Matrix9d point_line_distance2_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                                      const Eigen::Vector3d &e1);

// Squared distance of p to the plane through t0, t1, t2: ((p - t0) . n)^2 / |n|^2.
// Inputs: p; t0, t1, t2 not collinear. Outputs: value; gradient 12 (p, t0, t1, t2); Hessian.
double point_plane_distance2(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                             const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);
Vector12d point_plane_distance2_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                         const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);
Matrix12d point_plane_distance2_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                        const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);

// Squared distance of the lines through a0, a1 and b0, b1: ((b0 - a0) . n)^2 / |n|^2.
// Inputs: a0, a1, b0, b1 with (a1 - a0) x (b1 - b0) != 0. Outputs: value; gradient 12
// (a0, a1, b0, b1); Hessian 12 x 12.
double line_line_distance2(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                           const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);
Vector12d line_line_distance2_gradient(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                       const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);
Matrix12d line_line_distance2_hessian(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                      const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);

// ---- point-edge (segment), point-triangle, edge-edge with their closest-feature classes ----

// Closest feature of the segment e0 e1 to p: an end point or the interior (the projection's
// parameter clamped to [0, 1]; a segment of zero length is its end point e0).
enum class PointEdgeType { kE0, kE1, kInterior };
PointEdgeType point_edge_type(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                              const Eigen::Vector3d &e1);

// Squared distance of p to the segment e0 e1. Inputs: p, e0, e1. Outputs: value; gradient 9
// (p, e0, e1); Hessian 9 x 9 (of the classified piece; zero rows for the unused end point).
double point_edge_distance2(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                            const Eigen::Vector3d &e1);
Vector9d point_edge_distance2_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                                       const Eigen::Vector3d &e1);
Matrix9d point_edge_distance2_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                                      const Eigen::Vector3d &e1);

// Closest feature of the triangle t0 t1 t2 to p: a vertex, an edge (kE01 the edge t0 t1, ...)
// or the face. The face when the projection of p onto the plane has barycentric coordinates
// >= 0 (each computed as a signed area, ((t1 - p) x (t2 - p)) . n for t0, ...); otherwise the
// nearest of the three edges (each a point-edge classification). A triangle of zero area
// (|n| = 0) is its edges.
enum class PointTriangleType { kT0, kT1, kT2, kE01, kE12, kE20, kFace };
PointTriangleType point_triangle_type(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                      const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);

// Squared distance of p to the triangle t0 t1 t2 (all closest-feature cases).
// Inputs: p, t0, t1, t2. Outputs: value; gradient 12 (p, t0, t1, t2); Hessian 12 x 12.
double point_triangle_distance2(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);
Vector12d point_triangle_distance2_gradient(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                            const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);
Matrix12d point_triangle_distance2_hessian(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                           const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);

// Closest features of the segments a0 a1 and b0 b1: kInterior when the closest points of the two
// lines lie inside both segments (and the edges are not parallel: |u x v|^2 > 1e-16 |u|^2 |v|^2,
// u = a1 - a0, v = b1 - b0, see distance.cpp); otherwise the nearest of the four cases "an end
// point and the other segment", each classified as a point-edge pair.
enum class EdgeEdgeType {
  kA0B0,
  kA0B1,
  kA1B0,
  kA1B1,    // two end points
  kA0B,
  kA1B,    // an end point of a and the interior of b
  kAB0,
  kAB1,        // the interior of a and an end point of b
  kInterior    // both interiors (line-line)
};
EdgeEdgeType edge_edge_type(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                            const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);

// Squared distance of the segments a0 a1 and b0 b1 (all cases).
// Inputs: a0, a1, b0, b1. Outputs: value; gradient 12 (a0, a1, b0, b1); Hessian 12 x 12.
double edge_edge_distance2(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                           const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);
Vector12d edge_edge_distance2_gradient(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                       const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);
Matrix12d edge_edge_distance2_hessian(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                      const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);

// ---- the edge-edge mollifier (IPC section 4.3) ----

// eps = 1e-3 |A1 - A0|^2 |B1 - B0|^2 of a pair from its rest positions.
double edge_edge_mollifier_threshold(const Eigen::Vector3d &a0_rest, const Eigen::Vector3d &a1_rest,
                                     const Eigen::Vector3d &b0_rest,
                                     const Eigen::Vector3d &b1_rest);
// e(c) = (2 - c / eps) c / eps for c < eps, 1 beyond, c = |(a1 - a0) x (b1 - b0)|^2.
// Inputs: a0, a1, b0, b1; eps > 0. Outputs: value in [0, 1]; gradient 12; Hessian 12 x 12
// (zero when c >= eps).
double edge_edge_mollifier(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                           const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, double eps);
Vector12d edge_edge_mollifier_gradient(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                       const Eigen::Vector3d &b0, const Eigen::Vector3d &b1,
                                       double eps);
Matrix12d edge_edge_mollifier_hessian(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                                      const Eigen::Vector3d &b0, const Eigen::Vector3d &b1,
                                      double eps);

// ---- plain distances (no derivatives), from the closest points themselves ----

// Distance of p to the segment e0 e1, of p to the triangle t0 t1 t2, of two segments: the
// classification above, then |x - y| of the two closest points (not the square root of the
// smooth formula: the points are computed directly, which stays accurate for nearly parallel
// edges and points very close to large triangles). For the CCD and for checkers.
double point_edge_distance(const Eigen::Vector3d &p, const Eigen::Vector3d &e0,
                           const Eigen::Vector3d &e1);
double point_triangle_distance(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                               const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);
double edge_edge_distance(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                          const Eigen::Vector3d &b0, const Eigen::Vector3d &b1);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_DISTANCE_H
