#include "contact/candidates.h"

#include "linalg/general_format.h"

#include <algorithm>
#include <cmath>

using Eigen::Vector3d;

namespace PeriSISSM {

CandidateRange::CandidateRange(double dmin, double dhat, double edge0, double skin)
{
  longest_edge = edge0 > 0.0 ? std::max(kEdgeFactor * edge0, edge0 + 2.0 * skin) : 0.0;
  list_cutoff = dmin + dhat + 1.5 * longest_edge;
}

std::string missing_vertex_error(std::int64_t atom)
{
  return "a vertex of a triangle of atom " + std::to_string(atom) +
      " is neither owned nor a ghost atom here: the ghost cutoff is too short for the mesh "
      "(comm_modify cutoff)";
}

std::vector<ContactRole> contact_roles(int n, const int *mask, int groupbit, const int *mesh)
{
  std::vector<ContactRole> role(n, ContactRole::kNone);
  for (int i = 0; i < n; i++)
    if (mask[i] & groupbit)
      role[i] = (mesh && mesh[i]) ? ContactRole::kMeshVertex : ContactRole::kParticle;
  return role;
}

std::string CandidateRange::ghost_cutoff_error(double have, double edge0, double skin) const
{
  const double needed = ghost_cutoff(skin);
  if (!(have < needed)) return "";
  const std::string start =
      "the ghost cutoff " + general_format(have, 6) + " is shorter than a contact pair needs: ";
  const std::string end = "; set comm_modify cutoff " + general_format(needed, 6) + " or more";
  if (longest_edge == 0.0)
    return start + "dmin + dhat + skin = " + general_format(needed, 6) +
        " (the other particle of a pair with an owned one must be a ghost atom)" + end;
  return start + "dmin + dhat + skin + 2.5 x max(" + general_format(kEdgeFactor, 6) +
      " x the longest edge (" + general_format(edge0, 6) +
      "), that edge + 2 skin) = " + general_format(needed, 6) +
      " (the other vertices of a pair with an owned vertex must be ghost atoms)" + end;
}

std::string CandidateRange::edge_error(double edge, double skin) const
{
  if (covers(edge, skin)) return "";
  return "a mesh edge is " + general_format(edge, 6) +
      " long, more than the contact candidates of this run allow (the longest edge at the "
      "run's start, the larger of " +
      general_format(kEdgeFactor, 6) +
      " x it and it + 2 skin, less the neighbor skin: " + general_format(longest_edge - skin, 6) +
      "): start a new run (which measures the edges again) or use a smaller neighbor skin";
}

namespace {

  // a bounding sphere (centre, radius) and box (lo, hi)
  struct Bounds {
    Vector3d centre, lo, hi;
    double radius;
  };

  struct Tri {
    int v[3];
    Bounds b;
  };

  struct Edge {
    int v[2];
    Bounds b;
  };

  Bounds bounds_of(const Vector3d *y, int n)
  {
    Bounds b;
    b.centre = b.lo = b.hi = y[0];
    for (int k = 1; k < n; k++) {
      b.centre += y[k];
      b.lo = b.lo.cwiseMin(y[k]);
      b.hi = b.hi.cwiseMax(y[k]);
    }
    b.centre /= n;
    double r2 = 0.0;
    for (int k = 0; k < n; k++) r2 = std::max(r2, (y[k] - b.centre).squaredNorm());
    b.radius = std::sqrt(r2);
    return b;
  }

  // whether two sets are at least r apart by their bounds: their distance is at least the
  // distance of the centres less the radii, and at least the gap between the boxes
  bool apart(const Bounds &a, const Bounds &b, double r)
  {
    if ((a.centre - b.centre).norm() - a.radius - b.radius >= r) return true;
    for (int d = 0; d < 3; d++)
      if (a.lo[d] - b.hi[d] >= r || b.lo[d] - a.hi[d] >= r) return true;
    return false;
  }

  // The triangles and edges at each atom (owned or ghost, vertices at their images closest to
  // it), with their bounds, found once per atom when first needed
  class Primitives {
   public:
    explicit Primitives(const ContactAtoms &atoms) :
        a(atoms), tri_at(atoms.nall, -1), edge_at(atoms.nall, -1), tri_end(atoms.nall, 0),
        edge_end(atoms.nall, 0), around(atoms.nall)
    {
    }

    bool member(int k) const { return k >= 0 && a.role[k] == ContactRole::kMeshVertex; }
    Vector3d point(int k) const { return Vector3d(a.x[k][0], a.x[k][1], a.x[k][2]); }

    void find(int i)
    {
      if (tri_at[i] >= 0) return;
      tri_at[i] = (int) tris.size();
      edge_at[i] = (int) edges.size();
      others.clear();
      a.triangles(i, others);
      const std::int64_t *tag = a.tag;
      for (const std::array<int, 2> &w : others) {
        if (w[0] < 0 || w[1] < 0) {
          missing = tag[i];
          continue;
        }
        if (!member(w[0]) || !member(w[1])) continue;
        const Vector3d y[3] = {point(i), point(w[0]), point(w[1])};
        tris.push_back({{i, w[0], w[1]}, bounds_of(y, 3)});
        for (int e = 0; e < 2; e++) {
          bool seen = false;
          for (int g = edge_at[i]; g < (int) edges.size(); g++)
            seen = seen || tag[edges[g].v[1]] == tag[w[e]];
          if (seen) continue;
          const Vector3d ye[2] = {point(i), point(w[e])};
          edges.push_back({{i, w[e]}, bounds_of(ye, 2)});
        }
      }
      tri_end[i] = (int) tris.size();
      edge_end[i] = (int) edges.size();
      // (a sphere about the atom through its farthest edge end, and the box of the triangles)
      Bounds &u = around[i];
      u.centre = u.lo = u.hi = point(i);
      u.radius = 0.0;
      for (int t = tri_at[i]; t < tri_end[i]; t++) {
        u.lo = u.lo.cwiseMin(tris[t].b.lo);
        u.hi = u.hi.cwiseMax(tris[t].b.hi);
      }
      for (int e = edge_at[i]; e < edge_end[i]; e++)
        u.radius = std::max(u.radius, 2.0 * edges[e].b.radius);
    }

    const ContactAtoms &a;
    std::vector<int> tri_at, edge_at;    // first index, -1: not yet
    std::vector<int> tri_end, edge_end;
    std::vector<Bounds> around;    // the bounds of all the primitives at an atom
    std::vector<Tri> tris;
    std::vector<Edge> edges;
    std::vector<std::array<int, 2>> others;
    std::int64_t missing = 0;
  };

  // The pairs sorted by kind and then by their IDs. With IDs below 2^31 (every run of fewer
  // than two billion atoms) a pair's kind and IDs fit in two 64-bit words in that order, and
  // those keys with their indices are sorted (the 96-byte pairs are moved once, not at every
  // exchange of the sort); otherwise the pairs themselves.
  void sort_by_ids(std::vector<Candidate> &found)
  {
    const auto before = [](const Candidate &a, const Candidate &b) {
      if (a.type != b.type) return a.type < b.type;
      return std::lexicographical_compare(a.tag, a.tag + 4, b.tag, b.tag + 4);
    };
    constexpr std::int64_t kLimit = std::int64_t(1) << 31;
    bool small = true;
    for (const Candidate &c : found)
      for (int k = 0; k < 4; k++) small = small && c.tag[k] >= 0 && c.tag[k] < kLimit;
    if (!small) {
      std::sort(found.begin(), found.end(), before);
      return;
    }
    struct Key {
      std::uint64_t hi, lo;    // kind (2 bits), tag[0], tag[1] | tag[2], tag[3] (31 bits each)
      int n;
      bool operator<(const Key &o) const
      {
        return hi != o.hi ? hi < o.hi : (lo != o.lo ? lo < o.lo : n < o.n);
      }
    };
    std::vector<Key> keys(found.size());
    for (std::size_t n = 0; n < found.size(); n++) {
      const Candidate &c = found[n];
      const auto t = [&c](int k) {
        return (std::uint64_t) c.tag[k];
      };
      keys[n] = {((std::uint64_t) c.type << 62) | (t(0) << 31) | t(1), (t(2) << 31) | t(3),
                 (int) n};
    }
    std::sort(keys.begin(), keys.end());
    std::vector<Candidate> sorted;
    sorted.reserve(found.size());
    for (const Key &k : keys) sorted.push_back(found[k.n]);
    found = std::move(sorted);
  }

}    // namespace

std::int64_t find_candidates(const ContactAtoms &atoms, const NeighborView &list, double reach,
                             std::vector<Candidate> &candidates)
{
  const std::int64_t *tag = atoms.tag;
  const int nlocal = atoms.nlocal;
  Primitives prim(atoms);
  auto member = [&](int k) {
    return prim.member(k);
  };
  auto particle = [&](int k) {
    return atoms.role[k] == ContactRole::kParticle;
  };
  auto point = [&](int k) {
    return prim.point(k);
  };
  // the bounds of a point alone
  auto at = [&](int k) {
    const Vector3d y = point(k);
    return Bounds{y, y, y, 0.0};
  };

  std::vector<Candidate> found;
  // the pairs closer than reach (tested as they are found: a neighbor list with a wide skin
  // finds many times more pairs than it keeps)
  auto near = [&](const Candidate &c) {
    Vector3d y[4];
    c.gather(atoms.x, y);
    const double D = c.stencil().distance2(y);
    return D < reach * reach;
  };
  // A pair is found from every neighbor pair of its points that the list holds: each pair from
  // one of them only. The list holds every pair of points within its cutoff with an owned one
  // (of two owned points, from the one with the smaller ID; both calls below are made there),
  // and a pair closer than reach has its points within the cutoff as the top of candidates.h
  // says. So a point-triangle pair is taken from (p, the vertex of the triangle with the
  // smallest ID among those that are owned or whose p is), every vertex of the triangle being
  // within the cutoff of p; an edge-edge pair from its closest two ends of which one is owned
  // (ties: the smaller IDs), no farther apart than an owned end and the end of the other edge
  // nearer to its closest point (within the cutoff). The pairs that are not closer than reach
  // are dropped either way.
  auto owned_pair = [nlocal](int a, int b) {
    return a < nlocal || b < nlocal;
  };
  auto from_pt = [&](int p, const Tri &t) {
    int best = -1;
    for (int k = 0; k < 3; k++)
      if (owned_pair(p, t.v[k]) && (best < 0 || tag[t.v[k]] < tag[t.v[best]])) best = k;
    return best == 0;    // (t.v[0]: the vertex it was found at)
  };
  auto from_ee = [&](const Edge &a, const Edge &b) {
    int ba = -1, bb = -1;
    double best = 0.0;
    for (int k = 0; k < 2; k++)
      for (int l = 0; l < 2; l++) {
        const int u = a.v[k], w = b.v[l];
        if (!owned_pair(u, w)) continue;
        const double d2 = (point(u) - point(w)).squaredNorm();
        bool better = ba < 0 || d2 < best;
        if (!better && d2 == best) {
          const std::int64_t lo = std::min(tag[u], tag[w]), hi = std::max(tag[u], tag[w]);
          const std::int64_t blo = std::min(tag[a.v[ba]], tag[b.v[bb]]),
                             bhi = std::max(tag[a.v[ba]], tag[b.v[bb]]);
          better = lo < blo || (lo == blo && hi < bhi);
        }
        if (better) {
          ba = k;
          bb = l;
          best = d2;
        }
      }
    return ba == 0 && bb == 0;    // (a.v[0], b.v[0]: the atoms it was found at)
  };

  // a point-triangle pair in canonical order (the triangle's vertices by ID); none if p is one.
  // First the bounds (apart): most pairs the list finds are far
  auto add_pt = [&](int p, const Tri &t) {
    for (int k = 0; k < 3; k++)
      if (tag[t.v[k]] == tag[p]) return;
    if (!from_pt(p, t)) return;
    if (apart(at(p), t.b, reach)) return;
    int s[3] = {t.v[0], t.v[1], t.v[2]};
    std::sort(s, s + 3, [tag](int a, int b) {
      return tag[a] < tag[b];
    });
    Candidate c{StencilType::kPointTriangle,
                {tag[p], tag[s[0]], tag[s[1]], tag[s[2]]},
                {p, s[0], s[1], s[2]}};
    if (near(c)) found.push_back(c);
  };
  // an edge-edge pair in canonical order (each edge from its smaller ID, the edges by their
  // first IDs); none if they share a vertex
  auto add_ee = [&](const Edge &a, const Edge &b) {
    for (int k = 0; k < 2; k++)
      for (int l = 0; l < 2; l++)
        if (tag[a.v[k]] == tag[b.v[l]]) return;
    if (apart(a.b, b.b, reach)) return;
    if (!from_ee(a, b)) return;
    std::array<int, 2> u{a.v[0], a.v[1]}, w{b.v[0], b.v[1]};
    if (tag[u[1]] < tag[u[0]]) std::swap(u[0], u[1]);
    if (tag[w[1]] < tag[w[0]]) std::swap(w[0], w[1]);
    if (tag[w[0]] < tag[u[0]]) std::swap(u, w);
    Candidate c{StencilType::kEdgeEdge,
                {tag[u[0]], tag[u[1]], tag[w[0]], tag[w[1]]},
                {u[0], u[1], w[0], w[1]}};
    if (near(c)) found.push_back(c);
  };
  // a point-point pair in canonical order (by ID); none if they are or were bond partners
  auto add_pp = [&](int p, int q) {
    if (tag[q] < tag[p]) std::swap(p, q);
    if (atoms.were_partners && atoms.were_partners(p, q)) return;
    Candidate c{StencilType::kPointPoint, {tag[p], tag[q], 0, 0}, {p, q, -1, -1}};
    if (near(c)) found.push_back(c);
  };

  // (the list is full and symmetric between owned atoms: what a pair of owned atoms gives is
  // the same from either end, so it is taken from the end with the smaller ID only)
  for (int ii = 0; ii < list.inum; ii++) {
    const int i = list.ilist[ii];
    if (i >= nlocal || !(member(i) || particle(i))) continue;
    if (member(i)) prim.find(i);
    const int *jlist = list.firstneigh[i];
    for (int jj = 0; jj < list.numneigh[i]; jj++) {
      const int j = jlist[jj] & list.neighmask;
      if (tag[j] == tag[i] || (j < nlocal && tag[j] < tag[i])) continue;
      if (particle(i) && particle(j)) {
        add_pp(i, j);
        continue;
      }
      if (!member(j) && !particle(j)) continue;
      if (member(j)) prim.find(j);
      // (the primitives at i and at j, and the points i and j, lie within their atoms' bounds:
      // a point or an edge apart from all the primitives at the other atom is apart from each)
      if (member(i) && member(j) && apart(prim.around[i], prim.around[j], reach)) continue;
      if (member(j) && !apart(at(i), prim.around[j], reach))
        for (int t = prim.tri_at[j]; t < prim.tri_end[j]; t++) add_pt(i, prim.tris[t]);
      if (member(i) && !apart(at(j), prim.around[i], reach))
        for (int t = prim.tri_at[i]; t < prim.tri_end[i]; t++) add_pt(j, prim.tris[t]);
      if (member(i) && member(j))
        for (int a = prim.edge_at[i]; a < prim.edge_end[i]; a++) {
          if (apart(prim.edges[a].b, prim.around[j], reach)) continue;
          for (int b = prim.edge_at[j]; b < prim.edge_end[j]; b++)
            add_ee(prim.edges[a], prim.edges[b]);
        }
    }
  }

  // each pair once, in the order of its IDs
  sort_by_ids(found);
  const auto same = [](const Candidate &a, const Candidate &b) {
    return a.type == b.type && std::equal(a.tag, a.tag + 4, b.tag);
  };
  found.erase(std::unique(found.begin(), found.end(), same), found.end());

  for (Candidate &c : found) {
    if (c.type == StencilType::kEdgeEdge && atoms.rest_vector)
      c.eps = edge_edge_mollifier_threshold(Vector3d::Zero(), atoms.rest_vector(c.v[0], c.v[1]),
                                            Vector3d::Zero(), atoms.rest_vector(c.v[2], c.v[3]));
    if (atoms.owned) {
      int smallest = 0;
      for (int k = 0; k < c.nv(); k++) {
        c.own[k] = atoms.owned(c.tag[k]);
        if (c.tag[k] < c.tag[smallest]) smallest = k;
      }
      c.counts = c.own[smallest] >= 0;
    }
  }
  candidates = std::move(found);
  return prim.missing;
}

}    // namespace PeriSISSM
