// The mid-edge shape operator of a flat triangle mesh (see curvature.h).

#include "membrane/curvature.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace PeriSISSM {

namespace {

  using Id = std::int64_t;
  using Tri = std::array<Id, 3>;

  // the plate energy's weights over (xx, xy, yy): E = A D/2 sum_cd W_cd Q_c . Q_d
  void weights(double nu, double W[3][3])
  {
    const double w[3][3] = {{1.0, 0.0, nu}, {0.0, 2.0 * (1.0 - nu), 0.0}, {nu, 0.0, 1.0}};
    for (int c = 0; c < 3; c++)
      for (int d = 0; d < 3; d++) W[c][d] = w[c][d];
  }

  // x x^T of a unit vector as (xx, xy, yy)
  Eigen::Vector3d outer2(const Eigen::Vector2d &t)
  {
    return {t(0) * t(0), t(0) * t(1), t(1) * t(1)};
  }

  // The rest positions in the plane of one triangle: coordinates along e1, e2 (e1 along its
  // first edge, n = e1 x e2 its normal) relative to its first corner, each point checked to lie
  // in the plane; memoized, since a stencil's fits share most of their points.
  class Frame {
   public:
    Frame(const CurvatureMesh &mesh, const Tri &t) : mesh_(mesh), o_(t[0]) {}
    StencilStatus init(const Tri &t)
    {
      Eigen::Vector3d a, b;
      if (!mesh_.rest_offset(o_, t[1], a.data()) || !mesh_.rest_offset(o_, t[2], b.data()))
        return StencilStatus::missing;
      n_ = a.cross(b);
      h_ = (a.norm() + b.norm() + (b - a).norm()) / 3.0;
      if (!(n_.norm() > 1e-12 * h_ * h_)) return StencilStatus::degenerate;
      n_.normalize();
      e1_ = a.normalized();
      e2_ = n_.cross(e1_);
      return StencilStatus::ok;
    }
    double h() const { return h_; }
    StencilStatus at(Id v, Eigen::Vector2d &x)
    {
      const auto it = seen_.find(v);
      if (it != seen_.end()) {
        x = it->second;
        return StencilStatus::ok;
      }
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      if (v != o_ && !mesh_.rest_offset(o_, v, d.data())) return StencilStatus::missing;
      if (std::abs(d.dot(n_)) > kFlatTolerance * std::max(d.norm(), h_))
        return StencilStatus::not_flat;
      x = {d.dot(e1_), d.dot(e2_)};
      seen_.emplace(v, x);
      return StencilStatus::ok;
    }

   private:
    const CurvatureMesh &mesh_;
    Id o_;
    Eigen::Vector3d n_, e1_, e2_;
    double h_ = 0.0;
    std::map<Id, Eigen::Vector2d> seen_;
  };

  // the third vertices of the triangles at edge (a, b) other than the one with third vertex c
  bool across(const CurvatureMesh &mesh, Id a, Id b, Id c, std::vector<Id> &third)
  {
    std::vector<std::array<Id, 2>> at;
    if (!mesh.triangles_at(a, at)) return false;
    third.clear();
    for (const auto &o : at) {
      const Id x = o[0] == b ? o[1] : o[1] == b ? o[0] : -1;
      if (o[0] != b && o[1] != b) continue;
      if (x != c) third.push_back(x);
    }
    return true;
  }

  // The quadratic fitted to one triangle's stencil about its centroid c (the frame's plane):
  // rows of pinv give (value, slope x, slope y, k_xx, k_xy, k_yy) from the stencil's values.
  // The stencil: the corners and the far vertices of the triangles across its edges; least
  // squares over the corners' 1-rings when that is fewer than six points (an edge on the rim).
  struct Fit {
    std::vector<Id> vertex;
    Eigen::MatrixXd pinv;    // 6 x vertex.size()
    Eigen::Vector2d c;
  };

  StencilStatus fit_triangle(const CurvatureMesh &mesh, const Tri &t, Frame &frame, Fit &f)
  {
    f.vertex.assign(t.begin(), t.end());
    std::vector<Id> third;
    for (int k = 0; k < 3; k++) {
      if (!across(mesh, t[k], t[(k + 1) % 3], t[(k + 2) % 3], third)) return StencilStatus::missing;
      for (Id x : third)
        if (std::find(f.vertex.begin(), f.vertex.end(), x) == f.vertex.end()) f.vertex.push_back(x);
    }
    if (f.vertex.size() < 6) {
      std::set<Id> more;
      std::vector<std::array<Id, 2>> at;
      for (int k = 0; k < 3; k++) {
        if (!mesh.triangles_at(t[k], at)) return StencilStatus::missing;
        for (const auto &o : at) more.insert(o.begin(), o.end());
      }
      for (Id v : more)
        if (std::find(f.vertex.begin(), f.vertex.end(), v) == f.vertex.end()) f.vertex.push_back(v);
    }
    const int m = (int) f.vertex.size();
    if (m < 6) return StencilStatus::degenerate;
    std::vector<Eigen::Vector2d> x(m);
    for (int j = 0; j < m; j++) {
      const StencilStatus st = frame.at(f.vertex[j], x[j]);
      if (st != StencilStatus::ok) return st;
    }
    f.c = (x[0] + x[1] + x[2]) / 3.0;
    // in coordinates scaled by h (conditioning)
    const double h = frame.h();
    Eigen::MatrixXd B(m, 6);
    for (int j = 0; j < m; j++) {
      const Eigen::Vector2d d = (x[j] - f.c) / h;
      B.row(j) << 1.0, d(0), d(1), 0.5 * d(0) * d(0), d(0) * d(1), 0.5 * d(1) * d(1);
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd sv = svd.singularValues();
    if (!(sv(5) > 1e-8 * sv(0))) return StencilStatus::degenerate;
    f.pinv = svd.matrixV() * sv.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
    f.pinv.middleRows(1, 2) /= h;
    f.pinv.bottomRows(3) /= h * h;
    return StencilStatus::ok;
  }

  // A whole mesh by vertex index.
  class WholeMesh : public CurvatureMesh {
   public:
    WholeMesh(int nv, const double *X, const std::vector<std::array<int, 3>> &tri)
        : nv_(nv), X_(X), at_(nv)
    {
      for (const auto &t : tri)
        for (int k = 0; k < 3; k++) at_[t[k]].push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    }
    bool triangles_at(Id v, std::vector<std::array<Id, 2>> &others) const override
    {
      if (v < 0 || v >= nv_) return false;
      others = at_[v];
      return true;
    }
    bool rest_offset(Id from, Id to, double d[3]) const override
    {
      if (from < 0 || from >= nv_ || to < 0 || to >= nv_) return false;
      for (int k = 0; k < 3; k++) d[k] = X_[3 * to + k] - X_[3 * from + k];
      return true;
    }

   private:
    int nv_;
    const double *X_;
    std::vector<std::vector<std::array<Id, 2>>> at_;
  };

}    // namespace

// k_T = 1/A_T sum_i |e_i| (d_i - g_T . t_i) t_i t_i^T, d_i the mean over the triangles at edge
// i of their fits' slopes across it at its midpoint
StencilStatus triangle_stencil(const CurvatureMesh &mesh, const Tri &t, TriangleStencil &s)
{
  s = TriangleStencil();
  Frame frame(mesh, t);
  StencilStatus st = frame.init(t);
  if (st != StencilStatus::ok) return st;
  Eigen::Vector2d x[3];
  for (int k = 0; k < 3; k++) frame.at(t[k], x[k]);
  const Eigen::Vector2d p1 = x[1] - x[0], p2 = x[2] - x[0];
  const double area = 0.5 * std::abs(p1(0) * p2(1) - p1(1) * p2(0));
  // slope of the linear interpolant: g = G (w0, w1, w2)
  Eigen::Matrix2d M;
  M << p1(0), p1(1), p2(0), p2(1);
  const Eigen::Matrix2d Mi = M.inverse();
  Eigen::Matrix<double, 2, 3> G;
  G.col(0) = -Mi.col(0) - Mi.col(1);
  G.col(1) = Mi.col(0);
  G.col(2) = Mi.col(1);

  std::map<Id, Eigen::Vector3d> coef;
  auto add = [&coef](Id p, const Eigen::Vector3d &c) {
    auto it = coef.find(p);
    if (it == coef.end())
      coef.emplace(p, c);
    else
      it->second += c;
  };
  const Eigen::Vector2d centroid = (x[0] + x[1] + x[2]) / 3.0;
  Fit own;
  if ((st = fit_triangle(mesh, t, frame, own)) != StencilStatus::ok) return st;
  std::vector<Id> third;
  for (int k = 0; k < 3; k++) {
    const Id a = t[k], b = t[(k + 1) % 3];
    const Eigen::Vector2d e = x[(k + 1) % 3] - x[k], mid = 0.5 * (x[k] + x[(k + 1) % 3]);
    const double le = e.norm();
    Eigen::Vector2d tn(e(1) / le, -e(0) / le);
    if (tn.dot(mid - centroid) < 0.0) tn = -tn;
    const Eigen::Vector3d tt = outer2(tn);
    // the triangles at the edge: this one and those across it
    across(mesh, a, b, t[(k + 2) % 3], third);
    std::vector<Fit> sides(1 + third.size());
    sides[0] = own;
    for (std::size_t q = 0; q < third.size(); q++)
      if ((st = fit_triangle(mesh, {b, a, third[q]}, frame, sides[q + 1])) != StencilStatus::ok)
        return st;
    for (const Fit &f : sides) {
      const Eigen::Vector2d d = mid - f.c;
      const Eigen::VectorXd gx = f.pinv.row(1) + d(0) * f.pinv.row(3) + d(1) * f.pinv.row(4);
      const Eigen::VectorXd gy = f.pinv.row(2) + d(0) * f.pinv.row(4) + d(1) * f.pinv.row(5);
      const double w = le / (area * (double) sides.size());
      for (int j = 0; j < (int) f.vertex.size(); j++)
        add(f.vertex[j], w * (tn(0) * gx(j) + tn(1) * gy(j)) * tt);
    }
    for (int j = 0; j < 3; j++) add(t[j], -le / area * tn.dot(G.col(j)) * tt);
  }
  // the corners first, then the others by ID (the map's order)
  s.area = area;
  for (int k = 0; k < 3; k++) {
    s.vertex.push_back(t[k]);
    for (int c = 0; c < 3; c++) s.coef.push_back(coef[t[k]](c));
  }
  for (const auto &pc : coef) {
    if (pc.first == t[0] || pc.first == t[1] || pc.first == t[2]) continue;
    s.vertex.push_back(pc.first);
    for (int c = 0; c < 3; c++) s.coef.push_back(pc.second(c));
  }
  return StencilStatus::ok;
}

bool build_curvature_stencils(int nv, const double *X, const std::vector<std::array<int, 3>> &tri,
                              std::vector<CurvatureStencil> &stencils)
{
  stencils.clear();
  const WholeMesh mesh(nv, X, tri);
  std::vector<CurvatureStencil> out(tri.size());
  TriangleStencil s;
  for (std::size_t t = 0; t < tri.size(); t++) {
    if (triangle_stencil(mesh, {tri[t][0], tri[t][1], tri[t][2]}, s) != StencilStatus::ok)
      return false;
    out[t].vertex.assign(s.vertex.begin(), s.vertex.end());
    out[t].coef = s.coef;
    out[t].area = s.area;
  }
  stencils.swap(out);
  return true;
}

void curvature_weights(double area, double D, double nu, double adw[9])
{
  double W[3][3];
  weights(nu, W);
  for (int c = 0; c < 3; c++)
    for (int e = 0; e < 3; e++) adw[3 * c + e] = area * D * W[c][e];
}

double curvature_stress(const int *vertex, const double *coef, int m, const double adw[9],
                        const double *y, double S[9])
{
  // Q_c = sum_k coef_kc (y_k - y_0): the coefficients sum to zero, and differences of nearby
  // positions keep the round-off of a body far from the origin out of the curvature
  double Q[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};    // Q[c][d]: component d of Q_c
  const double *y0 = y + 3 * vertex[0];
  for (int k = 1; k < m; k++) {
    const double *yk = y + 3 * vertex[k];
    const double r[3] = {yk[0] - y0[0], yk[1] - y0[1], yk[2] - y0[2]};
    for (int c = 0; c < 3; c++)
      for (int d = 0; d < 3; d++) Q[c][d] += coef[3 * k + c] * r[d];
  }
  // S_c = A D sum_e W_ce Q_e = dE / dQ_c
  double E = 0.0;
  for (int c = 0; c < 3; c++)
    for (int d = 0; d < 3; d++) {
      double v = 0.0;
      for (int e = 0; e < 3; e++) v += adw[3 * c + e] * Q[e][d];
      S[3 * c + d] = v;
      E += 0.5 * v * Q[c][d];
    }
  return E;
}

double curvature_energy(const CurvatureStencil &s, const double *y, double D, double nu,
                        double *force)
{
  const int m = (int) s.vertex.size();
  double adw[9], S[9];
  curvature_weights(s.area, D, nu, adw);
  const double E = curvature_stress(s.vertex.data(), s.coef.data(), m, adw, y, S);
  if (force)
    for (int k = 0; k < m; k++) curvature_force(&s.coef[3 * k], S, force + 3 * k);
  return E;
}

double curvature_form(const CurvatureStencil &s, int k, int l, double nu)
{
  double W[3][3], sum = 0.0;
  weights(nu, W);
  for (int c = 0; c < 3; c++)
    for (int d = 0; d < 3; d++) sum += W[c][d] * s.coef[3 * k + c] * s.coef[3 * l + d];
  return sum;
}

void curvature_hessian(const CurvatureStencil &s, double D, double nu, std::vector<double> &h)
{
  const int m = (int) s.vertex.size();
  h.assign((std::size_t) m * m, 0.0);
  for (int k = 0; k < m; k++)
    for (int l = 0; l < m; l++) h[(std::size_t) m * k + l] = s.area * D * curvature_form(s, k, l, nu);
}

void curvature_factor(const CurvatureStencil &s, int k, double D, double nu, double a[3])
{
  // W = L L^T with L = [[1, 0, 0], [0, sqrt(2 (1 - nu)), 0], [nu, 0, sqrt(1 - nu^2)]]
  const double L[3][3] = {{1.0, 0.0, 0.0},
                          {0.0, std::sqrt(2.0 * (1.0 - nu)), 0.0},
                          {nu, 0.0, std::sqrt(std::max(0.0, 1.0 - nu * nu))}};
  const double scale = std::sqrt(s.area * D);
  const double *c = &s.coef[3 * k];
  for (int r = 0; r < 3; r++) a[r] = scale * (c[0] * L[0][r] + c[1] * L[1][r] + c[2] * L[2][r]);
}

}    // namespace PeriSISSM
