// Conservative continuous collision detection for barrier contact: additive CCD (ACCD) of
// Li, Kaufman, Jiang 2021, "Codimensional Incremental Potential Contact", section 5 and
// algorithm 1.
//
// The points of a pair move linearly, x_i(t) = x_i + t dx_i, over the step t in [0, 1]. After the
// mean displacement is subtracted (it moves both primitives alike), every point of primitive A
// moves at most at max_{i in A} |dx_i| (a point of a segment or triangle moves as a convex
// combination of its vertices) and likewise for B, so the gap g(t) = d(t) - dmin shrinks at most
// at the rate l = max_A |dx_i| + max_B |dx_j|: from a time t_k with gap g_k, the pair cannot
// reach dmin before t_k + g_k / l. ACCD advances by such safe sub-steps:
//
//   g0 = d(0) - dmin; the first sub-step (1 - s) g0 / l, then 0.9 g_k / l each,
//   until the gap at the next time would fall below s g0 (s the fraction kept, 0.1 by default);
//   return the last time whose gap is >= s g0 (or 1 when the step ends first).
//
// The answer t is conservative: the pair's gap stays positive over [0, t] (d > dmin), so t is
// never later than the true first time the distance reaches dmin. It can be earlier: for a head-on
// approach at constant speed t = (1 - s) t_true exactly; with tangential motion l overestimates the
// approach rate, and a near miss that comes within s g0 of dmin also stops the step. The number of
// sub-steps is at most about l / (0.9 s g0): large only for pairs that start close and move far
// (capped; see CcdOptions).
//
// LAMMPS-free, MPI-free: the step fraction of an update is the minimum over all pairs
// (contact/path_limit.h over the local candidates; the glue takes the MPI minimum).

#ifndef PERISISSM_CONTACT_CCD_H
#define PERISISSM_CONTACT_CCD_H

#include <Eigen/Core>

#include <cstddef>

namespace PeriSISSM {

struct CcdOptions {
  double dmin = 0.0;                // thickness: the distance the pair must keep (>= 0)
  double s = 0.1;                   // fraction of the initial gap left at the returned time
  double t_max = 1.0;               // the step's end
  long max_iterations = 1000000;    // sub-step cap
};

// What happened in one query (optional output).
struct CcdReport {
  long iterations = 0;             // distance evaluations after the first
  bool capped = false;             // max_iterations reached: t is the last safe time reached
  bool initially_close = false;    // the pair started at d <= dmin: t = 0
};

// The largest fraction t in [0, t_max] of the step that ACCD certifies (see above).
// Inputs: start positions and displacements of the pair's points (p; t0, t1, t2 for a point and a
// triangle, a0, a1; b0, b1 for two edges, p; q for two points);
// opt. Outputs: returns t (t_max when the pair stays apart over the whole step, 0 when it starts
// within dmin); report (when not null).
double point_triangle_ccd(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                          const Eigen::Vector3d &t1, const Eigen::Vector3d &t2,
                          const Eigen::Vector3d &dp, const Eigen::Vector3d &dt0,
                          const Eigen::Vector3d &dt1, const Eigen::Vector3d &dt2,
                          const CcdOptions &opt = CcdOptions(), CcdReport *report = nullptr);
double edge_edge_ccd(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1,
                     const Eigen::Vector3d &b0, const Eigen::Vector3d &b1,
                     const Eigen::Vector3d &da0, const Eigen::Vector3d &da1,
                     const Eigen::Vector3d &db0, const Eigen::Vector3d &db1,
                     const CcdOptions &opt = CcdOptions(), CcdReport *report = nullptr);
double point_point_ccd(const Eigen::Vector3d &p, const Eigen::Vector3d &q,
                       const Eigen::Vector3d &dp, const Eigen::Vector3d &dq,
                       const CcdOptions &opt = CcdOptions(), CcdReport *report = nullptr);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_CCD_H
