// The bending term of membranes over a distributed triangle mesh (doc/theory.rst, "Bending"):
// the hinge energy of membrane/hinge.h summed over the interior edges of the meshes, as a list
// of hinges in local indices and a pass over it, the same shape as the bond terms of peri/.
//
// A hinge is an edge (x0, x1) with the third vertices x2 of its triangle (x0, x1, x2) and x3 of
// (x1, x0, x3). Each rank lists the hinges with at least one owned vertex that takes a share,
// each once (build_hinges()); a pass evaluates every listed hinge once and gives each of its
// sharing owned vertices its own share: the force density, the diagonal block, a quarter of the
// energy (as an energy density) and its part of the virial. A hinge that straddles ranks is
// evaluated on each of them and no force goes to a ghost copy (no reverse communication); its
// other vertices are ghost copies, which the caller must provide (rows after the owned ones).
// LAMMPS-free.

#ifndef PERISISSM_MEMBRANE_BENDING_H
#define PERISISSM_MEMBRANE_BENDING_H

#include "peri/family.h"
#include "peri/fields.h"

#include <cstdint>
#include <vector>

namespace PeriSISSM {

struct HingeCouplings;

// One hinge of this rank's list.
struct Hinge {
  int v[4];         // local indices of its vertices, v[0] -> v[1] the edge (smaller ID first),
                    //   images closest to the owned vertex that listed it
  int own[4];       // owned index that takes vertex k's share, -1: none on this rank
  double theta0;    // rest angle
  double c;         // stiffness D |e0|^2 / (2 A0)
};

// What the hinge list needs to know about the mesh as this rank holds it: particle IDs,
// the triangles of the owned vertices, where a vertex is, and who takes shares.
class HingeMesh {
 public:
  virtual ~HingeMesh() = default;
  virtual int nlocal() const = 0;              // owned rows 0 .. nlocal-1
  virtual std::int64_t id(int i) const = 0;    // ID of the particle in row i (any row)
  virtual int ntri(int i) const = 0;           // triangles of owned vertex i
  // the other two vertices (a, b) of triangle k of owned vertex i, as IDs, in the triangle's
  // orientation (i, a, b)
  virtual void triangle(int i, int k, std::int64_t &a, std::int64_t &b) const = 0;
  // row of vertex ID t at its image closest to row i (owned or ghost), -1 if not on this rank
  virtual int image(int i, std::int64_t t) const = 0;
  // owned row of vertex ID t if it is owned here and takes shares of its hinges (a mesh vertex
  // of a type with bending), -1 otherwise
  virtual int sharer(std::int64_t t) const = 0;
  // bending modulus D of the particle in row i (owned or ghost), energy units; 0 without
  virtual double modulus(int i) const = 0;
  // whether the particle in row i bends by the plate energy (membrane/plate_bending.h) instead
  // of the hinges (an edge whose two ends do is no hinge), and its Poisson's ratio there
  virtual bool plate(int) const { return false; }
  virtual double poisson(int) const { return 0.0; }
};

// The hinges of this rank, each once, in the order of their edges' IDs (a vertex then sums its
// hinges' forces in the same order however the particles are ordered locally or split between
// ranks). Every owned sharer finds the hinges it belongs to: as an edge's end the edges (i, a)
// of its triangles; as a third vertex the edge (a, b) opposite it in each of its triangles,
// whose other triangle is in a's list. The smallest owned sharer of a hinge keeps it; the
// edge runs from the smaller ID to the larger. c = D |e0|^2 / (2 A0) with D the mean modulus
// of the edge's two ends (a hinge with D <= 0 is left out) and theta0 from the reference
// positions x0 (3 per row) relative to the edge's first vertex, in the reference box.
// Outputs: hinges (replaced); returns 0, or the ID of an owned vertex one of whose hinges has a
// vertex that is not on this rank (the hinges of the others are listed). An edge whose two
// ends are plate vertices is no hinge.
// With plate_edges true, the list has the other edges instead: those whose two ends are plate
// vertices, whose hinges stand in for the plate energy in the coarse level's matrix
// (peri/bond_stiffness.h; their pattern lies within the bonds' at a horizon of two edges).
std::int64_t build_hinges(const HingeMesh &mesh, const double *x0, const ReferenceBox &box,
                          std::vector<Hinge> &hinges, bool plate_edges = false);

// Where one bending pass puts its energy shares (either may be null): energy (+=) the sum of
// the shares, each a quarter of a hinge's energy over the vertex's volume; per_particle[i] (+=)
// the shares of owned particle i.
struct BendingEnergy {
  double *total = nullptr;
  double *per_particle = nullptr;
};

// One vertex's part (x_v - x_ref) (x) F_v of a bending element's virial, into the sinks (owned
// row i for the per-atom one). Summed over the element's vertices it is the element's virial
// whatever x_ref, when its forces F_v sum to zero (translation invariance).
void tally_virial(const Virial &virial, int i, const double *xv, const double *xref,
                  const double *F);

// The bending pass over a hinge list: for each hinge and each of its sharing vertices i (in
// list order, then vertex order), f_i += F_v / V_i with F_v = -dE/dx_v of the hinge
// (membrane/hinge.h), block[i] += its Gauss-Newton block 2 c g_v g_v^T / V_i (when block is not
// null), its energy share, and its part of the hinge's virial sum_v (x_v - x_0) (x) F_v (when
// virial has a sink). Inputs: p.x (owned and ghost rows), p.volume; outputs: p.f (owned rows).
void bending_pass(const std::vector<Hinge> &hinges, const Particles &p, double **block,
                  const BendingEnergy &energy, const Virial &virial);

// The bending term's part of the stable explicit time step (peri/stable_step.h). At rest
// (theta = theta0) a hinge's Hessian is its Gauss-Newton 2 c g g^T (g = d theta / d x), whose
// block (k, v) has the 2-norm 2 c |g_k| |g_v|; by the block Gershgorin theorem the squared
// frequencies of the hinges over the vertices' masses rho_i V_i are at most max_i G_i / rho_i,
//   G_i = sum over the hinges of owned vertex i (its place k) 2 c |g_k| sum_v |g_v| / V_i.
// The estimate of peri/stable_step.h with d_i = G_i, kStableStepSafety sqrt(2 rho_i / G_i), is
// 1.25 sqrt(2) / 2 = 0.88 times that bound's limit 2 sqrt(rho_i / G_i). The elastic estimate
// dt_e (d_e) and the bending's combine as the estimate of d_e + G_i:
//   1 / dt^2 = 1 / dt_e^2 + 1 / dt_b^2,   dt_b = stable_time_step(rho_i, G_i).
// Inputs: hinges, p.x (owned and ghost rows; g at these positions), p.volume, rho of the owned
//         rows (mass per volume); dt (owned rows) the elastic estimates, +infinity for none.
// Outputs: dt of the owned rows that take a share of a hinge combined as above; stiffness
//          (when not null, owned rows, +=) G_i.
void bending_stable_steps(const std::vector<Hinge> &hinges, const Particles &p, const double *rho,
                          double *dt, double *stiffness = nullptr);

// The combination above of a bending term's G_i (owned rows; 0: none) with the estimates dt:
// dt_i combined where G_i > 0, and stiffness (when not null, +=) G_i.
void combine_stable_steps(const std::vector<double> &G, const double *rho, double *dt,
                          double *stiffness);

// The hinges in the current positions p.x for an assembled stiffness (peri/bond_stiffness.h):
// vertices and rows of each, and with gradients true sqrt(2 c) d theta / d x_v (grad left empty
// otherwise).
void hinge_couplings(const std::vector<Hinge> &hinges, const Particles &p, bool gradients,
                     HingeCouplings &couplings);

}    // namespace PeriSISSM

#endif    // PERISISSM_MEMBRANE_BENDING_H
