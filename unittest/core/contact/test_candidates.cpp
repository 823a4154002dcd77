// Tests of the broad phase (contact/candidates.h) on a scene of two facing triangulated sheets
// and particles between them (contact_scene.h): the candidates are exactly the pairs a brute
// force over all primitives finds closer than the reach (no pair sharing a vertex, particles
// that were partners excluded), each once, in canonical vertex order, sorted by kind and IDs
// (with ghost atoms: those with an owned point);
// local indices point at the atoms with those IDs; eps, own and counts from the caller's rest
// shape and owners; a triangle vertex missing from the atoms is reported; the ranges of a run
// (the list's cutoff finds every candidate).

#include "contact/candidates.h"

#include "contact_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

using namespace PeriSISSM;
using Eigen::Vector3d;
using PeriSISSMContactTest::Scene;

namespace {

using Key = std::tuple<int, std::int64_t, std::int64_t, std::int64_t, std::int64_t>;

Key key_of(const Candidate &c)
{
  return Key((int) c.type, c.tag[0], c.tag[1], c.tag[2], c.tag[3]);
}

// every pair of primitives closer than reach, keyed by kind and canonical IDs
std::set<Key> brute_force(const Scene &s, double reach,
                          const std::function<bool(int, int)> &partners)
{
  std::set<Key> keys;
  auto p3 = [&](int k) {
    return Vector3d(s.pos[k][0], s.pos[k][1], s.pos[k][2]);
  };
  auto sorted = [&](std::vector<int> v) {
    std::sort(v.begin(), v.end(), [&](int a, int b) {
      return s.tag[a] < s.tag[b];
    });
    return v;
  };
  const CollisionStencil &pt = CollisionStencil::of(StencilType::kPointTriangle);
  const CollisionStencil &ee = CollisionStencil::of(StencilType::kEdgeEdge);
  const CollisionStencil &pp = CollisionStencil::of(StencilType::kPointPoint);
  // the edges, each once, from its smaller ID
  std::set<std::pair<int, int>> edge_set;
  for (const auto &t : s.triangles)
    for (int k = 0; k < 3; k++) {
      int a = t[k], b = t[(k + 1) % 3];
      if (s.tag[b] < s.tag[a]) std::swap(a, b);
      edge_set.insert({a, b});
    }
  const std::vector<std::pair<int, int>> edges(edge_set.begin(), edge_set.end());
  for (int p = 0; p < s.n(); p++) {
    if (s.role[p] == ContactRole::kNone) continue;
    for (const auto &t : s.triangles) {
      if (t[0] == p || t[1] == p || t[2] == p) continue;
      const std::vector<int> v = sorted({t[0], t[1], t[2]});
      const Vector3d y[4] = {p3(p), p3(v[0]), p3(v[1]), p3(v[2])};
      if (pt.distance2(y) < reach * reach)
        keys.insert(Key(0, s.tag[p], s.tag[v[0]], s.tag[v[1]], s.tag[v[2]]));
    }
  }
  for (std::size_t a = 0; a < edges.size(); a++)
    for (std::size_t b = a + 1; b < edges.size(); b++) {
      auto u = edges[a], w = edges[b];
      if (u.first == w.first || u.first == w.second || u.second == w.first || u.second == w.second)
        continue;
      if (s.tag[w.first] < s.tag[u.first]) std::swap(u, w);
      const Vector3d y[4] = {p3(u.first), p3(u.second), p3(w.first), p3(w.second)};
      if (ee.distance2(y) < reach * reach)
        keys.insert(Key(1, s.tag[u.first], s.tag[u.second], s.tag[w.first], s.tag[w.second]));
    }
  for (int p = 0; p < s.n(); p++)
    for (int q = 0; q < s.n(); q++) {
      if (s.role[p] != ContactRole::kParticle || s.role[q] != ContactRole::kParticle) continue;
      if (!(s.tag[p] < s.tag[q]) || (partners && partners(p, q))) continue;
      const Vector3d y[2] = {p3(p), p3(q)};
      if (pp.distance2(y) < reach * reach) keys.insert(Key(2, s.tag[p], s.tag[q], 0, 0));
    }
  return keys;
}

// two sheets 0.3 apart (spacing 1, the second shifted by (0.4, 0.3)), three particles between
// them and a fourth beside the first, one atom outside the contact
Scene two_sheets(unsigned seed)
{
  Scene s;
  s.sheet(5, 1.0, 0.0, 0.0, 0.0);
  s.sheet(5, 1.0, 0.3, 0.4, 0.3);
  s.add(1.5, 1.5, 0.15, ContactRole::kParticle);
  s.add(1.6, 1.6, 0.15, ContactRole::kParticle);
  s.add(2.5, 1.2, 0.16, ContactRole::kParticle);
  s.add(1.5, -0.2, 0.0, ContactRole::kParticle);
  s.add(2.2, 2.2, 0.1, ContactRole::kNone);
  // the list covers r + 1.5 L (L = sqrt(2), the diagonals)
  s.finish(0.5 + 1.5 * std::sqrt(2.0) + 1e-9, seed);
  return s;
}

}    // namespace

TEST(Candidates, AreThePairsWithinReachEachOnceInOrder)
{
  for (unsigned seed : {1u, 2u, 3u}) {
    const Scene s = two_sheets(seed);
    for (double reach : {0.2, 0.35, 0.5}) {
      std::vector<Candidate> found;
      EXPECT_EQ(find_candidates(s.atoms(), s.list(), reach, found), 0);
      const std::set<Key> expected = brute_force(s, reach, nullptr);
      std::vector<Key> keys;
      for (const Candidate &c : found) keys.push_back(key_of(c));
      EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
      EXPECT_EQ(std::set<Key>(keys.begin(), keys.end()).size(), keys.size());
      EXPECT_EQ(std::set<Key>(keys.begin(), keys.end()), expected) << seed << " " << reach;
      int kinds[3] = {0, 0, 0};
      for (const Candidate &c : found) {
        kinds[(int) c.type]++;
        for (int k = 0; k < c.nv(); k++) EXPECT_EQ(s.tag[c.v[k]], c.tag[k]);
        if (c.type == StencilType::kPointPoint) {
          EXPECT_EQ(c.v[2], -1);
          EXPECT_EQ(c.tag[3], 0);
        }
      }
      if (reach >= 0.35) {
        EXPECT_GT(kinds[0], 10);
        EXPECT_GT(kinds[1], 10);
        EXPECT_GT(kinds[2], 0);
      }
    }
  }
}

// IDs of 2^31 and more (sorted as pairs, not as packed keys): the same pairs in the same order
TEST(Candidates, LargeIdsGiveTheSameOrder)
{
  Scene s = two_sheets(4);
  std::vector<Candidate> small, large;
  find_candidates(s.atoms(), s.list(), 0.5, small);
  const std::int64_t offset = std::int64_t(1) << 33;
  for (std::int64_t &t : s.tag) t += offset;
  find_candidates(s.atoms(), s.list(), 0.5, large);
  ASSERT_EQ(small.size(), large.size());
  ASSERT_GT(small.size(), 20u);
  for (std::size_t n = 0; n < small.size(); n++) {
    EXPECT_EQ(small[n].type, large[n].type);
    for (int k = 0; k < small[n].nv(); k++) {
      EXPECT_EQ(small[n].v[k], large[n].v[k]);
      EXPECT_EQ(small[n].tag[k] + offset, large[n].tag[k]);
    }
  }
}

// A process that owns only the first nlocal atoms (the others ghosts, its list the owned atoms'
// full lists): the pairs within reach that have an owned point, each once
TEST(Candidates, OwnedAndGhostAtomsGiveThePairsWithAnOwnedPointEachOnce)
{
  for (unsigned seed : {1u, 2u}) {
    const Scene s = two_sheets(seed);
    std::vector<int> local_of(s.n() + 1);
    for (int i = 0; i < s.n(); i++) local_of[s.tag[i]] = i;
    for (int nlocal : {7, 25, 38, 52}) {
      ContactAtoms atoms = s.atoms();
      atoms.nlocal = nlocal;
      NeighborView list = s.list();
      list.inum = nlocal;
      for (double reach : {0.35, 0.5}) {
        std::vector<Candidate> found;
        EXPECT_EQ(find_candidates(atoms, list, reach, found), 0);
        std::set<Key> expected;
        for (const Key &k : brute_force(s, reach, nullptr)) {
          const std::int64_t t[4] = {std::get<1>(k), std::get<2>(k), std::get<3>(k),
                                     std::get<4>(k)};
          bool owned = false;
          for (std::int64_t id : t) owned = owned || (id > 0 && local_of[id] < nlocal);
          if (owned) expected.insert(k);
        }
        std::vector<Key> keys;
        for (const Candidate &c : found) keys.push_back(key_of(c));
        EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
        EXPECT_EQ(std::set<Key>(keys.begin(), keys.end()).size(), keys.size());
        EXPECT_EQ(std::set<Key>(keys.begin(), keys.end()), expected)
            << seed << " " << nlocal << " " << reach;
        EXPECT_GT(expected.size(), 5u);
      }
    }
  }
}

// eps from the rest shape, own and counts from the owner of each ID
TEST(Candidates, RestShapeAndOwners)
{
  const Scene s = two_sheets(6);
  ContactAtoms atoms = s.atoms();
  // the rest shape: the positions scaled by 2; atoms with odd IDs owned here
  atoms.rest_vector = [&s](int a, int b) {
    return Vector3d(2.0 * (s.pos[b][0] - s.pos[a][0]), 2.0 * (s.pos[b][1] - s.pos[a][1]),
                    2.0 * (s.pos[b][2] - s.pos[a][2]));
  };
  atoms.owned = [&s](std::int64_t t) {
    for (int i = 0; i < s.n(); i++)
      if (s.tag[i] == t) return (t % 2) ? i : -1;
    return -1;
  };
  std::vector<Candidate> found;
  find_candidates(atoms, s.list(), 0.5, found);
  int ee = 0, counted = 0;
  for (const Candidate &c : found) {
    for (int k = 0; k < c.nv(); k++) EXPECT_EQ(c.own[k], (c.tag[k] % 2) ? c.v[k] : -1);
    const std::int64_t smallest = *std::min_element(c.tag, c.tag + c.nv());
    EXPECT_EQ(c.counts, smallest % 2 == 1);
    counted += c.counts;
    if (c.type != StencilType::kEdgeEdge) {
      EXPECT_EQ(c.eps, 0.0);
      continue;
    }
    ee++;
    const Vector3d ra = atoms.rest_vector(c.v[0], c.v[1]), rb = atoms.rest_vector(c.v[2], c.v[3]);
    EXPECT_EQ(c.eps, edge_edge_mollifier_threshold(Vector3d::Zero(), ra, Vector3d::Zero(), rb));
    EXPECT_GT(c.eps, 0.0);
  }
  EXPECT_GT(ee, 0);
  EXPECT_GT(counted, 0);
  EXPECT_LT(counted, (int) found.size());
}

TEST(Candidates, PartnersAreNoPair)
{
  const Scene s = two_sheets(4);
  // the first two particles (local 50 and 51) were bonded
  auto partners = [](int a, int b) {
    return std::min(a, b) == 50 && std::max(a, b) == 51;
  };
  ContactAtoms atoms = s.atoms();
  atoms.were_partners = partners;
  std::vector<Candidate> with, without;
  find_candidates(s.atoms(), s.list(), 0.5, without);
  find_candidates(atoms, s.list(), 0.5, with);
  EXPECT_EQ(without.size(), with.size() + 1);
  std::set<Key> keys;
  for (const Candidate &c : with) keys.insert(key_of(c));
  EXPECT_EQ(keys, brute_force(s, 0.5, partners));
}

TEST(Candidates, ReportsAMissingTriangleVertex)
{
  const Scene s = two_sheets(5);
  ContactAtoms atoms = s.atoms();
  const auto all = atoms.triangles;
  atoms.triangles = [all](int i, std::vector<std::array<int, 2>> &others) {
    all(i, others);
    if (i == 12) others.push_back({-1, 13});
  };
  std::vector<Candidate> found;
  EXPECT_EQ(find_candidates(atoms, s.list(), 0.5, found), s.tag[12]);
  EXPECT_EQ(missing_vertex_error(1234567890123),
            "a vertex of a triangle of atom 1234567890123 is neither owned nor a ghost atom here: "
            "the ghost cutoff is too short for the mesh (comm_modify cutoff)");
}

// The run's ranges: Lmax the larger of 1.5 L0 and L0 + 2 skin (0 without edges), the list
// cutoff r + 1.5 Lmax, the ghost cutoff that + skin + Lmax, an edge covered while L + skin <=
// Lmax; a list of that cutoff + skin finds the same candidates within r + skin as the full list
TEST(Candidates, RangeOfARun)
{
  const CandidateRange small(0.01, 0.1, 2.0, 0.2);    // 1.5 x 2 = 3 > 2 + 0.4
  EXPECT_EQ(small.longest_edge, 3.0);
  EXPECT_DOUBLE_EQ(small.list_cutoff, 0.11 + 4.5);
  EXPECT_DOUBLE_EQ(small.ghost_cutoff(0.2), 0.11 + 4.5 + 0.2 + 3.0);
  EXPECT_TRUE(small.covers(2.75, 0.2));
  EXPECT_FALSE(small.covers(2.85, 0.2));
  const CandidateRange large(0.0, 0.1, 2.0, 1.5);    // 2 + 3 > 1.5 x 2
  EXPECT_EQ(large.longest_edge, 5.0);
  EXPECT_DOUBLE_EQ(large.list_cutoff, 0.1 + 7.5);
  const CandidateRange none(0.01, 0.1, 0.0, 0.2);
  EXPECT_EQ(none.longest_edge, 0.0);
  EXPECT_EQ(none.list_cutoff, 0.01 + 0.1);
  EXPECT_EQ(none.ghost_cutoff(0.2), 0.01 + 0.1 + 0.2);
  EXPECT_EQ(CandidateRange().longest_edge, 0.0);

  // the sheets' longest edge is a diagonal; every atom of the scene owned
  const double dmin = 0.02, dhat = 0.2, skin = 0.1;
  const CandidateRange range(dmin, dhat, std::sqrt(2.0), skin);
  for (unsigned seed : {4u, 5u}) {
    Scene near =
        PeriSISSMContactTest::facing_sheets(0.25, 0.12, 1.55, range.list_cutoff + skin, seed);
    Scene all = PeriSISSMContactTest::facing_sheets(0.25, 0.12, 1.55, 100.0, seed);
    std::vector<Candidate> from_near, from_all;
    find_candidates(near.atoms(), near.list(), dmin + dhat + skin, from_near);
    find_candidates(all.atoms(), all.list(), dmin + dhat + skin, from_all);
    EXPECT_LT(near.flat.size(), all.flat.size());
    ASSERT_EQ(from_near.size(), from_all.size());
    EXPECT_GT(from_near.size(), 20u);
    for (std::size_t k = 0; k < from_near.size(); k++)
      EXPECT_EQ(key_of(from_near[k]), key_of(from_all[k]));
  }
}

// The errors of a run's ranges: a ghost cutoff shorter than ghost_cutoff() (and only then),
// without and with mesh edges, and an edge that covers() refuses, with the numbers that say
// what to change
TEST(Candidates, RangeErrors)
{
  const CandidateRange none(0.01, 0.1, 0.0, 0.2);    // needs 0.31
  EXPECT_EQ(none.ghost_cutoff_error(0.32, 0.0, 0.2), "");
  EXPECT_EQ(none.ghost_cutoff_error(0.3, 0.0, 0.2),
            "the ghost cutoff 0.3 is shorter than a contact pair needs: dmin + dhat + skin = "
            "0.31 (the other particle of a pair with an owned one must be a ghost atom); set "
            "comm_modify cutoff 0.31 or more");
  // edge 0.02 x sqrt 2, skin 0.005: Lmax = 1.5 x 0.0282843 = 0.0424264, needs 0.012 + 2.5 Lmax
  const double edge0 = 0.02 * std::sqrt(2.0);
  const CandidateRange cloth(0.0005, 0.0065, edge0, 0.005);
  EXPECT_EQ(cloth.ghost_cutoff_error(0.1181, edge0, 0.005), "");
  EXPECT_EQ(cloth.ghost_cutoff_error(0.118, edge0, 0.005),
            "the ghost cutoff 0.118 is shorter than a contact pair needs: dmin + dhat + skin + "
            "2.5 x max(1.5 x the longest edge (0.0282843), that edge + 2 skin) = 0.118066 (the "
            "other vertices of a pair with an owned vertex must be ghost atoms); set comm_modify "
            "cutoff 0.118066 or more");
  const CandidateRange small(0.01, 0.1, 2.0, 0.2);    // Lmax 3: edges up to 2.8
  EXPECT_EQ(small.edge_error(2.75, 0.2), "");
  EXPECT_EQ(small.edge_error(2.85, 0.2),
            "a mesh edge is 2.85 long, more than the contact candidates of this run allow (the "
            "longest edge at the run's start, the larger of 1.5 x it and it + 2 skin, less the "
            "neighbor skin: 2.8): start a new run (which measures the edges again) or use a "
            "smaller neighbor skin");
}

// The roles: outside the group none, in it mesh vertices where mesh is nonzero, else particles
TEST(Candidates, Roles)
{
  const int mask[5] = {1, 3, 2, 3, 1};
  const int mesh[5] = {0, 4, 4, 0, 7};
  using R = ContactRole;
  EXPECT_EQ(contact_roles(5, mask, 2, mesh),
            (std::vector<R>{R::kNone, R::kMeshVertex, R::kMeshVertex, R::kParticle, R::kNone}));
  EXPECT_EQ(contact_roles(5, mask, 1, nullptr),
            (std::vector<R>{R::kParticle, R::kParticle, R::kNone, R::kParticle, R::kParticle}));
  EXPECT_TRUE(contact_roles(0, mask, 1, mesh).empty());
}
