// The plate bending term of membranes over a distributed triangle mesh (see plate_bending.h).

#include "membrane/plate_bending.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace PeriSISSM {

namespace {

  using Id = std::int64_t;
  using Key = std::array<Id, 3>;

  // a triangle's corners in its orientation with the smallest ID first
  Key key_of(Id a, Id b, Id c)
  {
    if (b < a && b < c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
  }

  // The mesh as this rank holds it, by ID, seen from owned row `anchor` (the rows of the
  // vertices are their images closest to it).
  class LocalMesh : public CurvatureMesh {
   public:
    LocalMesh(const HingeMesh &mesh, const double *x0, const ReferenceBox &box)
        : mesh_(mesh), x0_(x0), box_(box)
    {
    }
    void anchor(int i) { anchor_ = i; }
    int row(Id v) const { return mesh_.image(anchor_, v); }
    bool triangles_at(Id v, std::vector<std::array<Id, 2>> &others) const override
    {
      const int r = row(v);
      if (r < 0) return false;
      const int n = mesh_.ntri(r);
      others.resize(n);
      for (int k = 0; k < n; k++) {
        std::int64_t a, b;
        mesh_.triangle(r, k, a, b);
        others[k] = {a, b};
      }
      return true;
    }
    bool rest_offset(Id from, Id to, double d[3]) const override
    {
      const int a = row(from), b = row(to);
      if (a < 0 || b < 0) return false;
      for (int k = 0; k < 3; k++) d[k] = x0_[3 * b + k] - x0_[3 * a + k];
      if (box_.any()) box_.image(d[0], d[1], d[2]);
      return true;
    }

   private:
    const HingeMesh &mesh_;
    const double *x0_;
    const ReferenceBox &box_;
    int anchor_ = 0;
  };

}    // namespace

PlateProblem PlateBending::build(const HingeMesh &mesh, const double *x0, const ReferenceBox &box)
{
  list_.clear();
  couplings_ = PlateCouplings();
  couplings_.first.assign(1, 0);
  make_pass_data();    // (empty until the list is complete)
  PlateProblem problem;
  LocalMesh local(mesh, x0, box);
  const int nlocal = mesh.nlocal();

  // the candidates, each with the owned sharer that found it first
  std::map<Key, int> candidates;
  std::vector<std::array<Id, 2>> at, at2;
  for (int i = 0; i < nlocal; i++) {
    const Id id = mesh.id(i);
    if (mesh.sharer(id) != i || !mesh.plate(i)) continue;
    local.anchor(i);
    auto found = around_.find(id);
    if (found == around_.end()) {
      // the triangles of its ring's vertices and those across their edges (once per vertex)
      std::vector<Key> keys;
      std::set<Id> ring = {id};
      local.triangles_at(id, at);
      for (const auto &o : at) ring.insert(o.begin(), o.end());
      for (Id v : ring) {
        if (!local.triangles_at(v, at)) return {StencilStatus::missing, id, {id, v, v}};
        for (const auto &o : at) {
          const Id t[3] = {v, o[0], o[1]};
          keys.push_back(key_of(t[0], t[1], t[2]));
          for (int k = 0; k < 3; k++) {
            const Id a = t[k], b = t[(k + 1) % 3];
            if (!local.triangles_at(a, at2))
              return {StencilStatus::missing, id, {t[0], t[1], t[2]}};
            for (const auto &o2 : at2)
              if (o2[0] == b || o2[1] == b) keys.push_back(key_of(a, o2[0], o2[1]));
          }
        }
      }
      std::sort(keys.begin(), keys.end());
      keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
      found = around_.emplace(id, std::move(keys)).first;
    }
    for (const Key &t : found->second) {
      const int ra = local.row(t[0]), rb = local.row(t[1]), rc = local.row(t[2]);
      if (ra < 0 || rb < 0 || rc < 0) return {StencilStatus::missing, id, t};
      if (mesh.plate(ra) && mesh.plate(rb) && mesh.plate(rc)) candidates.emplace(t, i);
    }
  }

  // their stencils (made once), the ones that hold an owned sharer, in local rows
  for (const auto &kc : candidates) {
    const Key &t = kc.first;
    local.anchor(kc.second);
    auto it = cache_.find(t);
    if (it == cache_.end()) {
      TriangleStencil s;
      const StencilStatus st = triangle_stencil(local, t, s);
      if (st != StencilStatus::ok) return {st, mesh.id(kc.second), t};
      it = cache_.emplace(t, std::move(s)).first;
    }
    const TriangleStencil &s = it->second;
    const int m = (int) s.vertex.size();
    PlateTriangle tri;
    tri.own.resize(m);
    bool any = false;
    for (int k = 0; k < m; k++) {
      tri.own[k] = mesh.sharer(s.vertex[k]);
      any = any || tri.own[k] >= 0;
    }
    if (!any) continue;
    tri.stencil.vertex.resize(m);
    for (int k = 0; k < m; k++) {
      tri.stencil.vertex[k] = local.row(s.vertex[k]);
      if (tri.stencil.vertex[k] < 0) return {StencilStatus::missing, mesh.id(kc.second), t};
    }
    for (int k = 0; k < 3; k++) {
      tri.D += mesh.modulus(tri.stencil.vertex[k]) / 3.0;
      tri.nu += mesh.poisson(tri.stencil.vertex[k]) / 3.0;
    }
    if (!(tri.D > 0.0)) continue;
    tri.stencil.coef = s.coef;
    tri.stencil.area = s.area;
    list_.push_back(std::move(tri));
  }
  make_couplings();
  make_pass_data();
  return problem;
}

void PlateBending::pass(const Particles &p, double **block, const BendingEnergy &energy,
                        const Virial &virial) const
{
  const double *x = p.x;
  double *f = p.f;
  const bool tally_energy = energy.total || energy.per_particle;
  const PassData &d = flat_;
  const int ntri = (int) d.scale.size();
  for (int t = 0; t < ntri; t++) {
    const int first = d.first[t], m = d.first[t + 1] - first;
    const int *row = &d.row[first];
    const double *coef = &d.coef[3 * first];
    double S[9];
    const double E = curvature_stress(row, coef, m, &d.adw[9 * t], x, S);
    const double *x0 = x + 3 * row[0];
    for (int k = 0; k < m; k++) {
      const int i = d.own[first + k];
      if (i < 0) continue;
      const double vi = p.volume[i];
      double F[3];
      curvature_force(coef + 3 * k, S, F);
      for (int c = 0; c < 3; c++) f[3 * i + c] += F[c] / vi;
      if (block) {
        // the Hessian's diagonal block h_kk I
        const double hkk = d.form[first + k] * (d.scale[t] / vi);
        for (int c = 0; c < 3; c++) block[i][c] += hkk;
      }
      if (tally_energy && k < 3) {
        const double e = E / (3.0 * vi);
        if (energy.total) *energy.total += e;
        if (energy.per_particle) energy.per_particle[i] += e;
      }
      if (virial.any()) tally_virial(virial, i, x + 3 * row[k], x0, F);
    }
  }
}

void PlateBending::stable_steps(const Particles &p, const double *rho, double *dt,
                                double *stiffness) const
{
  std::vector<double> G(p.nlocal, 0.0), h;
  for (const PlateTriangle &t : list_) {
    curvature_hessian(t.stencil, t.D, t.nu, h);
    const int m = (int) t.stencil.vertex.size();
    for (int k = 0; k < m; k++) {
      const int i = t.own[k];
      if (i < 0) continue;
      double sum = 0.0;
      for (int l = 0; l < m; l++) sum += std::abs(h[(std::size_t) m * k + l]);
      G[i] += sum / p.volume[i];
    }
  }
  combine_stable_steps(G, rho, dt, stiffness);
}

void PlateBending::make_couplings()
{
  PlateCouplings &plates = couplings_;
  plates.first.assign(1, 0);
  plates.vertex.clear();
  plates.row.clear();
  plates.a.clear();
  for (const PlateTriangle &t : list_) {
    const CurvatureStencil &s = t.stencil;
    for (std::size_t k = 0; k < s.vertex.size(); k++) {
      plates.vertex.push_back(s.vertex[k]);
      plates.row.push_back(t.own[k]);
      double a[3];
      curvature_factor(s, (int) k, t.D, t.nu, a);
      plates.a.insert(plates.a.end(), a, a + 3);
    }
    plates.first.push_back((int) plates.vertex.size());
  }
}

void PlateBending::make_pass_data()
{
  PassData &d = flat_;
  d = PassData();
  d.first.assign(1, 0);
  for (const PlateTriangle &t : list_) {
    const CurvatureStencil &s = t.stencil;
    const int m = (int) s.vertex.size();
    for (int k = 0; k < m; k++) {
      d.row.push_back(s.vertex[k]);
      d.own.push_back(t.own[k]);
      d.form.push_back(curvature_form(s, k, k, t.nu));
    }
    d.coef.insert(d.coef.end(), s.coef.begin(), s.coef.end());
    double adw[9];
    curvature_weights(s.area, t.D, t.nu, adw);
    d.adw.insert(d.adw.end(), adw, adw + 9);
    d.scale.push_back(s.area * t.D);
    d.first.push_back((int) d.row.size());
  }
}

}    // namespace PeriSISSM
