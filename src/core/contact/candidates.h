// Candidate contact pairs and the broad phase that finds them (as the IPC Toolkit's Candidates
// and BroadPhase), from plain arrays: positions, IDs and kinds of the owned and ghost atoms, the
// triangles at each mesh vertex, and a neighbor list.
//
// Pairs. Every point-triangle pair (a vertex and a triangle) and every edge-edge pair of the
// meshes whose primitives are in the group, except those that share a vertex (a vertex and the
// triangles of its own 1-ring, two edges with a common end). The group's atoms that are not
// mesh vertices are volumetric particles, i.e. points: they form point-point pairs with each
// other (unless the caller's were_partners() says they are or were bonded) and point-triangle
// pairs with the group's triangles.
//
// Completeness. A pair of primitives closer than r has vertices closer than r + 1.5 L (L the
// longest edge): for a point p and a triangle T with closest point q, every vertex of T is
// within L of q, so |p - t_k| < r + L; for two edges with closest points qa, qb, an end a_k is
// within L of qa and the nearer end b_c of the other within L/2 of qb. So every pair with an
// owned vertex o is found from o and a neighbor j of o within r + 1.5 L: as (point o, the
// triangles at j), (point j, the triangles at o) and (the edges at o, the edges at j), or
// (particle o, particle j). Each pair is taken from one such neighbor pair only: a point and a
// triangle from the point and the triangle's vertex with the smallest ID among those that share
// a list entry with it (one of the two owned: every vertex is within r + L), two edges from
// their two closest ends with an owned one (no farther apart than o and b_c). The broad phase
// keeps the pairs closer than reach (the caller's r + skin), testing bounding spheres and boxes
// of the primitives first.
//
// Order. Each pair once, in canonical vertex order (a triangle's vertices by ID, each edge from
// its smaller ID, the edges by their first IDs, two points by ID), the pairs sorted by kind and
// then by their IDs: a vertex that sums its shares over the pairs in this order gets the same
// sum however the atoms are numbered locally or split between ranks. LAMMPS-free.

#ifndef PERISISSM_CONTACT_CANDIDATES_H
#define PERISISSM_CONTACT_CANDIDATES_H

#include "contact/stencil.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace PeriSISSM {

// A candidate pair: its kind, the IDs of its points in canonical order (point-point: tag[2],
// tag[3] are 0) and the local indices of the images used (point-point: v[2], v[3] are -1)
struct Candidate {
  StencilType type;
  std::int64_t tag[4];
  int v[4];
  double eps = 0.0;                 // edge-edge: the mollifier threshold of the rest shape
  int own[4] = {-1, -1, -1, -1};    // local indices of its owned vertices (-1: others)
  bool counts = false;              // this rank counts it (owns its smallest ID)

  const CollisionStencil &stencil() const { return CollisionStencil::of(type); }
  int nv() const { return type == StencilType::kPointPoint ? 2 : 4; }
  // its points' positions in x into y[0 .. nv() - 1]
  void gather(const double *const *x, Eigen::Vector3d *y) const
  {
    for (int k = 0; k < nv(); k++) y[k] = Eigen::Vector3d(x[v[k]][0], x[v[k]][1], x[v[k]][2]);
  }
};

// What an atom is to the contact
enum class ContactRole : char { kNone = 0, kMeshVertex = 1, kParticle = 2 };

// A neighbor list (LAMMPS's layout): the atoms ilist[0 .. inum - 1], the neighbors of atom i
// firstneigh[i][0 .. numneigh[i] - 1], each masked with neighmask (to drop special bits)
struct NeighborView {
  int inum = 0;
  const int *ilist = nullptr;
  const int *numneigh = nullptr;
  int *const *firstneigh = nullptr;
  int neighmask = ~0;
};

// The roles of atoms 0 .. n - 1: none outside the group (!(mask[i] & groupbit)), in it mesh
// vertices (mesh[i] != 0; mesh nullptr: there are none) and particles (the others)
std::vector<ContactRole> contact_roles(int n, const int *mask, int groupbit, const int *mesh);

// The atoms of one rank: nlocal owned then ghosts, nall in all
struct ContactAtoms {
  int nlocal = 0;
  int nall = 0;
  const double *const *x = nullptr;     // positions (nall x 3)
  const std::int64_t *tag = nullptr;    // IDs (nall)
  const ContactRole *role = nullptr;    // (nall)
  // the triangles at mesh vertex i: for each, the local indices of its other two vertices at
  // their images closest to i (-1: the vertex is neither owned nor a ghost here)
  std::function<void(int i, std::vector<std::array<int, 2>> &others)> triangles;
  // whether two particles (local indices) are or were bond partners (none if empty)
  std::function<bool(int a, int b)> were_partners;
  // the rest-shape vector from atom a to atom b (local indices; the minimum image in periodic
  // boxes): the edge-edge mollifier thresholds (none if empty: eps stays 0)
  std::function<Eigen::Vector3d(int a, int b)> rest_vector;
  // the local index of the owned atom with an ID, -1 if it is not owned here (none if empty:
  // own and counts stay unset)
  std::function<int(std::int64_t tag)> owned;
};

// The candidate pairs with an owned vertex closer than reach, sorted and unique (see the top of
// this file), with eps from rest_vector() and own and counts from owned() (a pair counts on
// the rank that owns its smallest ID, so that it counts once over all ranks). Inputs: the
// atoms; a full neighbor list of the owned atoms (symmetric between owned atoms); reach.
// Output: the candidates; returns the ID of an atom with a triangle vertex missing from the
// atoms (0: none).
std::int64_t find_candidates(const ContactAtoms &atoms, const NeighborView &list, double reach,
                             std::vector<Candidate> &candidates);
// The error for the atom find_candidates() returned: a triangle vertex missing from the atoms
std::string missing_vertex_error(std::int64_t atom);

// The ranges of the broad phase for a run with contact range r = dmin + dhat and neighbor skin
// s, from the longest mesh edge L0 at the run's start (0: no mesh edges): the edges are assumed
// no longer than Lmax = max(kEdgeFactor L0, L0 + 2 s) (0 without edges); a neighbor list of
// cutoff r + 1.5 Lmax + s at a build gives every pair closer than r + s (the completeness
// argument above); the other vertices of a pair with an owned vertex lie within that cutoff +
// Lmax of it (the ghost cutoff needed). A measured edge L stays covered while L + s <= Lmax.
struct CandidateRange {
  // edges may stretch by 50% less the skin (by a skin when the skin is large)
  static constexpr double kEdgeFactor = 1.5;
  double longest_edge = 0.0;    // Lmax
  double list_cutoff = 0.0;     // r + 1.5 Lmax (the skin not included)

  CandidateRange() = default;
  CandidateRange(double dmin, double dhat, double edge0, double skin);
  double ghost_cutoff(double skin) const { return list_cutoff + skin + longest_edge; }
  bool covers(double edge, double skin) const { return !(edge + skin > longest_edge); }
  // The error for a ghost cutoff have < ghost_cutoff(skin), the longest edge at the run's start
  // edge0 (0: none) and what comm_modify cutoff needs; empty when have is long enough.
  std::string ghost_cutoff_error(double have, double edge0, double skin) const;
  // The error for a measured edge that covers() refuses; empty when it is covered.
  std::string edge_error(double edge, double skin) const;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_CANDIDATES_H
