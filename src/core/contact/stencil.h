// The kinds of contact pair (as the IPC Toolkit's CollisionStencil): a point and a triangle
// (p; t0 t1 t2), two edges (a0 a1; b0 b1) and two points (p; q). Each kind gives, for its points
// y[0 .. num_vertices() - 1] in that order, the squared distance, the barrier's energy, gradient
// and Hessian (barrier.h), the additive CCD fraction (ccd.h) and the lagged friction data
// (friction.h); closing() bounds how much a move can shrink the distance. A glue loop over
// pairs of all kinds calls CollisionStencil::of(type) and never tests the kind itself.
//
// eps is the edge-edge mollifier threshold (edge_edge_mollifier_threshold(), from the rest
// shape); the other kinds ignore it. Gradients and Hessians are 12 values / 12 x 12 with zeros
// past the pair's vertices. LAMMPS-free.

#ifndef PERISISSM_CONTACT_STENCIL_H
#define PERISISSM_CONTACT_STENCIL_H

#include "contact/barrier.h"
#include "contact/ccd.h"
#include "contact/friction.h"

#include <algorithm>

#include <Eigen/Core>

namespace PeriSISSM {

enum class StencilType { kPointTriangle = 0, kEdgeEdge = 1, kPointPoint = 2 };

class CollisionStencil {
 public:
  virtual ~CollisionStencil() = default;

  // the stencil of a kind (one shared instance per kind)
  static const CollisionStencil &of(StencilType type);

  virtual StencilType type() const = 0;
  // the pair's points: 4 (point-triangle, edge-edge) or 2 (point-point)
  virtual int num_vertices() const = 0;
  // the first primitive's points y[0 .. first_vertices() - 1] (p, or a0 a1); the rest are the
  // second's
  virtual int first_vertices() const = 0;
  // "point-triangle", "edge-edge", "point-point" (messages)
  virtual const char *name() const = 0;

  virtual double distance2(const Eigen::Vector3d *y) const = 0;
  virtual double barrier_energy(const Eigen::Vector3d *y, double eps,
                                const BarrierParameters &prm) const = 0;
  virtual Vector12d barrier_gradient(const Eigen::Vector3d *y, double eps,
                                     const BarrierParameters &prm) const = 0;
  // both (the energy returned, the gradient in g) from the squared distance D = distance2(y)
  virtual double barrier_energy_gradient(const Eigen::Vector3d *y, double eps, double D,
                                         const BarrierParameters &prm, Vector12d &g) const = 0;
  // psd: projected to positive semi-definite
  virtual Matrix12d barrier_hessian(const Eigen::Vector3d *y, double eps,
                                    const BarrierParameters &prm, bool psd) const = 0;
  // the fraction of the move y -> y + dy that additive CCD certifies (ccd.h)
  virtual double ccd(const Eigen::Vector3d *y, const Eigen::Vector3d *dy,
                     const CcdOptions &opt) const = 0;
  virtual FrictionPair friction_pair(const Eigen::Vector3d *y, double eps,
                                     const BarrierParameters &prm) const = 0;

  // How much a move of the points by the lengths len[k] (k < num_vertices()) can shrink the
  // pair's distance: the largest move of a point of each primitive, summed (the distance of two
  // sets moves by at most the largest displacement within each).
  double closing(const double *len) const;
};

// CollisionStencil::closing() of the stencil of a kind, without its virtual calls (the form for
// loops over all candidates): the largest move of a point of each primitive, summed
inline double closing(StencilType type, const double *len)
{
  switch (type) {
    case StencilType::kPointTriangle:
      return len[0] + std::max(std::max(len[1], len[2]), len[3]);
    case StencilType::kEdgeEdge:
      return std::max(len[0], len[1]) + std::max(len[2], len[3]);
    default:
      return len[0] + len[1];
  }
}

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_STENCIL_H
