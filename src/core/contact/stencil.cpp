#include "contact/stencil.h"

#include <algorithm>

using Eigen::Vector3d;

namespace PeriSISSM {

namespace {

  class PointTriangleStencil final : public CollisionStencil {
   public:
    StencilType type() const override { return StencilType::kPointTriangle; }
    int num_vertices() const override { return 4; }
    int first_vertices() const override { return 1; }
    const char *name() const override { return "point-triangle"; }
    double distance2(const Vector3d *y) const override
    {
      return point_triangle_distance2(y[0], y[1], y[2], y[3]);
    }
    double barrier_energy(const Vector3d *y, double, const BarrierParameters &prm) const override
    {
      return point_triangle_barrier_energy(y[0], y[1], y[2], y[3], prm);
    }
    Vector12d barrier_gradient(const Vector3d *y, double,
                               const BarrierParameters &prm) const override
    {
      return point_triangle_barrier_gradient(y[0], y[1], y[2], y[3], prm);
    }
    double barrier_energy_gradient(const Vector3d *y, double, double D,
                                   const BarrierParameters &prm, Vector12d &g) const override
    {
      return point_triangle_barrier(y[0], y[1], y[2], y[3], D, prm, g);
    }
    Matrix12d barrier_hessian(const Vector3d *y, double, const BarrierParameters &prm,
                              bool psd) const override
    {
      return point_triangle_barrier_hessian(y[0], y[1], y[2], y[3], prm, psd);
    }
    double ccd(const Vector3d *y, const Vector3d *dy, const CcdOptions &opt) const override
    {
      return point_triangle_ccd(y[0], y[1], y[2], y[3], dy[0], dy[1], dy[2], dy[3], opt);
    }
    FrictionPair friction_pair(const Vector3d *y, double,
                               const BarrierParameters &prm) const override
    {
      return point_triangle_friction_pair(y[0], y[1], y[2], y[3], prm);
    }
  };

  class EdgeEdgeStencil final : public CollisionStencil {
   public:
    StencilType type() const override { return StencilType::kEdgeEdge; }
    int num_vertices() const override { return 4; }
    int first_vertices() const override { return 2; }
    const char *name() const override { return "edge-edge"; }
    double distance2(const Vector3d *y) const override
    {
      return edge_edge_distance2(y[0], y[1], y[2], y[3]);
    }
    double barrier_energy(const Vector3d *y, double eps,
                          const BarrierParameters &prm) const override
    {
      return edge_edge_barrier_energy(y[0], y[1], y[2], y[3], eps, prm);
    }
    Vector12d barrier_gradient(const Vector3d *y, double eps,
                               const BarrierParameters &prm) const override
    {
      return edge_edge_barrier_gradient(y[0], y[1], y[2], y[3], eps, prm);
    }
    double barrier_energy_gradient(const Vector3d *y, double eps, double D,
                                   const BarrierParameters &prm, Vector12d &g) const override
    {
      return edge_edge_barrier(y[0], y[1], y[2], y[3], eps, D, prm, g);
    }
    Matrix12d barrier_hessian(const Vector3d *y, double eps, const BarrierParameters &prm,
                              bool psd) const override
    {
      return edge_edge_barrier_hessian(y[0], y[1], y[2], y[3], eps, prm, psd);
    }
    double ccd(const Vector3d *y, const Vector3d *dy, const CcdOptions &opt) const override
    {
      return edge_edge_ccd(y[0], y[1], y[2], y[3], dy[0], dy[1], dy[2], dy[3], opt);
    }
    FrictionPair friction_pair(const Vector3d *y, double eps,
                               const BarrierParameters &prm) const override
    {
      return edge_edge_friction_pair(y[0], y[1], y[2], y[3], eps, prm);
    }
  };

  class PointPointStencil final : public CollisionStencil {
   public:
    StencilType type() const override { return StencilType::kPointPoint; }
    int num_vertices() const override { return 2; }
    int first_vertices() const override { return 1; }
    const char *name() const override { return "point-point"; }
    double distance2(const Vector3d *y) const override { return point_point_distance2(y[0], y[1]); }
    double barrier_energy(const Vector3d *y, double, const BarrierParameters &prm) const override
    {
      return point_point_barrier_energy(y[0], y[1], prm);
    }
    Vector12d barrier_gradient(const Vector3d *y, double,
                               const BarrierParameters &prm) const override
    {
      Vector12d g = Vector12d::Zero();
      g.head<6>() = point_point_barrier_gradient(y[0], y[1], prm);
      return g;
    }
    double barrier_energy_gradient(const Vector3d *y, double, double D,
                                   const BarrierParameters &prm, Vector12d &g) const override
    {
      Vector6d g6;
      const double E = point_point_barrier(y[0], y[1], D, prm, g6);
      g.setZero();
      g.head<6>() = g6;
      return E;
    }
    Matrix12d barrier_hessian(const Vector3d *y, double, const BarrierParameters &prm,
                              bool psd) const override
    {
      Matrix12d H = Matrix12d::Zero();
      H.topLeftCorner<6, 6>() = point_point_barrier_hessian(y[0], y[1], prm, psd);
      return H;
    }
    double ccd(const Vector3d *y, const Vector3d *dy, const CcdOptions &opt) const override
    {
      return point_point_ccd(y[0], y[1], dy[0], dy[1], opt);
    }
    FrictionPair friction_pair(const Vector3d *y, double,
                               const BarrierParameters &prm) const override
    {
      return point_point_friction_pair(y[0], y[1], prm);
    }
  };

}    // namespace

const CollisionStencil &CollisionStencil::of(StencilType type)
{
  static const PointTriangleStencil pt;
  static const EdgeEdgeStencil ee;
  static const PointPointStencil pp;
  switch (type) {
    case StencilType::kPointTriangle:
      return pt;
    case StencilType::kEdgeEdge:
      return ee;
    default:
      return pp;
  }
}

double CollisionStencil::closing(const double *len) const
{
  return PeriSISSM::closing(type(), len);
}

}    // namespace PeriSISSM
