// The mid-edge shape operator of a flat triangle mesh (see curvature.h).

#include "membrane/curvature.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace PeriSISSM {

namespace {

  // The quadratic fitted to one triangle's stencil, about its centroid c (rest 2D frame):
  // rows of pinv give (value, slope x, slope y, k_xx, k_xy, k_yy) from the stencil's values.
  struct Fit {
    std::vector<int> vertex;
    Eigen::MatrixXd pinv;    // 6 x vertex.size()
    Eigen::Vector2d c;
  };

  using Edge = std::pair<int, int>;
  Edge edge_of(int a, int b)
  {
    return {std::min(a, b), std::max(a, b)};
  }

  // x x^T of a unit vector as (xx, xy, yy)
  Eigen::Vector3d outer2(const Eigen::Vector2d &t)
  {
    return {t(0) * t(0), t(0) * t(1), t(1) * t(1)};
  }

}    // namespace

bool build_curvature_stencils(int nv, const double *X, const std::vector<std::array<int, 3>> &tri,
                              std::vector<CurvatureStencil> &stencils)
{
  stencils.clear();
  const int nt = (int) tri.size();
  if (nt == 0) return true;

  // the rest plane: the first triangle's normal n, e1 along its first edge, e2 = n x e1
  const Eigen::Map<const Eigen::Matrix3Xd> P(X, 3, nv);
  const Eigen::Vector3d o = P.col(tri[0][0]);
  Eigen::Vector3d e1 = P.col(tri[0][1]) - o, n = e1.cross(P.col(tri[0][2]) - o);
  double size = 0.0;
  for (int i = 0; i < nv; i++) size = std::max(size, (P.col(i) - o).norm());
  if (!(n.norm() > 1e-12 * size * size)) return false;
  n.normalize();
  e1.normalize();
  const Eigen::Vector3d e2 = n.cross(e1);
  std::vector<Eigen::Vector2d> x(nv);
  for (int i = 0; i < nv; i++) {
    const Eigen::Vector3d d = P.col(i) - o;
    if (std::abs(d.dot(n)) > 1e-9 * size) return false;
    x[i] = {d.dot(e1), d.dot(e2)};
  }

  // edges with their triangles and those triangles' third vertices; 1-rings; mean edge length
  std::map<Edge, std::vector<std::pair<int, int>>> edges;
  std::vector<std::set<int>> ring(nv);
  double h = 0.0;
  for (int t = 0; t < nt; t++)
    for (int k = 0; k < 3; k++) {
      const int a = tri[t][k], b = tri[t][(k + 1) % 3], c = tri[t][(k + 2) % 3];
      edges[edge_of(a, b)].push_back({t, c});
      ring[a].insert(tri[t].begin(), tri[t].end());
      h += (x[b] - x[a]).norm() / (3.0 * nt);
    }

  // the quadratic of each triangle, in coordinates scaled by h (conditioning)
  std::vector<Fit> fits(nt);
  for (int t = 0; t < nt; t++) {
    Fit &f = fits[t];
    f.vertex.assign(tri[t].begin(), tri[t].end());
    for (int k = 0; k < 3; k++)
      for (const auto &tc : edges[edge_of(tri[t][k], tri[t][(k + 1) % 3])])
        if (tc.first != t &&
            std::find(f.vertex.begin(), f.vertex.end(), tc.second) == f.vertex.end())
          f.vertex.push_back(tc.second);
    if (f.vertex.size() < 6) {
      std::set<int> more;
      for (int k = 0; k < 3; k++) more.insert(ring[tri[t][k]].begin(), ring[tri[t][k]].end());
      for (int v : more)
        if (std::find(f.vertex.begin(), f.vertex.end(), v) == f.vertex.end()) f.vertex.push_back(v);
    }
    f.c = (x[tri[t][0]] + x[tri[t][1]] + x[tri[t][2]]) / 3.0;
    const int m = (int) f.vertex.size();
    if (m < 6) return false;
    Eigen::MatrixXd B(m, 6);
    for (int j = 0; j < m; j++) {
      const Eigen::Vector2d d = (x[f.vertex[j]] - f.c) / h;
      B.row(j) << 1.0, d(0), d(1), 0.5 * d(0) * d(0), d(0) * d(1), 0.5 * d(1) * d(1);
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    if (!(s(5) > 1e-8 * s(0))) return false;
    f.pinv = svd.matrixV() * s.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
    f.pinv.middleRows(1, 2) /= h;
    f.pinv.bottomRows(3) /= h * h;
  }

  // k_T = 1/A_T sum_i |e_i| (d_i - g_T . t_i) t_i t_i^T
  stencils.resize(nt);
  for (int t = 0; t < nt; t++) {
    const std::array<int, 3> &v = tri[t];
    const Eigen::Vector2d p1 = x[v[1]] - x[v[0]], p2 = x[v[2]] - x[v[0]];
    const double area = 0.5 * std::abs(p1(0) * p2(1) - p1(1) * p2(0));
    if (!(area > 0.0)) return false;
    // slope of the linear interpolant: g = G (w0, w1, w2)
    Eigen::Matrix2d M;
    M << p1(0), p1(1), p2(0), p2(1);
    const Eigen::Matrix2d Mi = M.inverse();
    Eigen::Matrix<double, 2, 3> G;
    G.col(0) = -Mi.col(0) - Mi.col(1);
    G.col(1) = Mi.col(0);
    G.col(2) = Mi.col(1);
    std::map<int, Eigen::Vector3d> coef;
    auto add = [&coef](int p, const Eigen::Vector3d &c) {
      auto it = coef.find(p);
      if (it == coef.end())
        coef.emplace(p, c);
      else
        it->second += c;
    };
    const Eigen::Vector2d centroid = (x[v[0]] + x[v[1]] + x[v[2]]) / 3.0;
    for (int k = 0; k < 3; k++) {
      const int a = v[k], b = v[(k + 1) % 3];
      const Eigen::Vector2d e = x[b] - x[a], mid = 0.5 * (x[a] + x[b]);
      const double le = e.norm();
      Eigen::Vector2d tn(e(1) / le, -e(0) / le);
      if (tn.dot(mid - centroid) < 0.0) tn = -tn;
      const Eigen::Vector3d tt = outer2(tn);
      const auto &sides = edges[edge_of(a, b)];
      for (const auto &tc : sides) {
        const Fit &f = fits[tc.first];
        const Eigen::Vector2d d = mid - f.c;
        const Eigen::VectorXd gx = f.pinv.row(1) + d(0) * f.pinv.row(3) + d(1) * f.pinv.row(4);
        const Eigen::VectorXd gy = f.pinv.row(2) + d(0) * f.pinv.row(4) + d(1) * f.pinv.row(5);
        const double w = le / (area * (double) sides.size());
        for (int j = 0; j < (int) f.vertex.size(); j++)
          add(f.vertex[j], w * (tn(0) * gx(j) + tn(1) * gy(j)) * tt);
      }
      for (int j = 0; j < 3; j++) add(v[j], -le / area * tn.dot(G.col(j)) * tt);
    }
    CurvatureStencil &s = stencils[t];
    s.area = area;
    for (const auto &pc : coef) {
      s.vertex.push_back(pc.first);
      for (int c = 0; c < 3; c++) s.coef.push_back(pc.second(c));
    }
  }
  return true;
}

double curvature_energy(const CurvatureStencil &s, const double *y, double D, double nu,
                        double *force)
{
  const int m = (int) s.vertex.size();
  double Q[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};    // Q[c][d]: component d of Q_c
  for (int k = 0; k < m; k++)
    for (int c = 0; c < 3; c++)
      for (int d = 0; d < 3; d++) Q[c][d] += s.coef[3 * k + c] * y[3 * s.vertex[k] + d];
  const double W[3][3] = {{1.0, 0.0, nu}, {0.0, 2.0 * (1.0 - nu), 0.0}, {nu, 0.0, 1.0}};
  // S_c = A D sum_d W_cd Q_d = dE / dQ_c
  double S[3][3], E = 0.0;
  for (int c = 0; c < 3; c++)
    for (int d = 0; d < 3; d++) {
      S[c][d] = 0.0;
      for (int e = 0; e < 3; e++) S[c][d] += s.area * D * W[c][e] * Q[e][d];
      E += 0.5 * S[c][d] * Q[c][d];
    }
  if (force)
    for (int k = 0; k < m; k++)
      for (int d = 0; d < 3; d++) {
        double g = 0.0;
        for (int c = 0; c < 3; c++) g += s.coef[3 * k + c] * S[c][d];
        force[3 * k + d] = -g;
      }
  return E;
}

void curvature_hessian(const CurvatureStencil &s, double D, double nu, std::vector<double> &h)
{
  const int m = (int) s.vertex.size();
  const double W[3][3] = {{1.0, 0.0, nu}, {0.0, 2.0 * (1.0 - nu), 0.0}, {nu, 0.0, 1.0}};
  h.assign((std::size_t) m * m, 0.0);
  for (int k = 0; k < m; k++)
    for (int l = 0; l < m; l++) {
      double sum = 0.0;
      for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) sum += W[c][d] * s.coef[3 * k + c] * s.coef[3 * l + d];
      h[(std::size_t) m * k + l] = s.area * D * sum;
    }
}

}    // namespace PeriSISSM
