// The plate bending term of membranes over a distributed triangle mesh (doc/theory.rst,
// "Bending"): the mid-edge curvature energy of membrane/curvature.h, the Kirchhoff plate's
// D/2 [(tr k)^2 - 2 (1 - nu) det k] per area on any triangulation, summed over the triangles of
// the meshes, as a list in local indices and a pass over it (the shape of the hinge list of
// membrane/bending.h).
//
// A triangle's stencil reaches two rings of triangles around it. Each rank lists the triangles
// whose stencil holds an owned sharer (HingeMesh::sharer), each once, with the stencil's other
// vertices as ghost copies (images closest to the owned vertex that found the triangle); a pass
// evaluates every listed triangle and gives each owned sharer of its stencil its force, diagonal
// block and part of the virial, and each owned sharer among its corners a third of its energy.
// A triangle that straddles ranks is evaluated on each of them and no force goes to a ghost copy
// (no reverse communication). The stencils depend on the rest shape only and are kept across
// rebuilds of the list. LAMMPS-free.

#ifndef PERISISSM_MEMBRANE_PLATE_BENDING_H
#define PERISISSM_MEMBRANE_PLATE_BENDING_H

#include "membrane/bending.h"
#include "membrane/curvature.h"
#include "peri/bond_stiffness.h"

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace PeriSISSM {

// One triangle of this rank's list.
struct PlateTriangle {
  CurvatureStencil stencil;    // vertex: local rows (its three corners first)
  std::vector<int> own;        // per stencil vertex: the owned row that takes its share, -1: none
  double D = 0.0;              // the mean bending modulus of its corners
  double nu = 0.0;             // the mean Poisson's ratio of its corners
};

// What a failed build found: the stencil of triangle (its corners' IDs) found by owned vertex
// `vertex`, and why it could not be made (missing: a vertex beyond this rank's ghosts).
struct PlateProblem {
  StencilStatus status = StencilStatus::ok;
  std::int64_t vertex = 0;
  std::array<std::int64_t, 3> triangle = {0, 0, 0};
  bool ok() const { return status == StencilStatus::ok; }
};

class PlateBending {
 public:
  // The list of this rank (replaced): the triangles whose three corners are plate vertices
  // (HingeMesh::plate) with a mean modulus D > 0 and whose stencil holds an owned sharer, in the
  // order of their corners' IDs. A vertex v is in triangle T's stencil when it is in the fit of
  // T or of a triangle across one of T's edges; v is in the fit of T' when it is a corner of T',
  // the far vertex of a triangle across an edge of T', or (T' at the rim, fewer than six such
  // points) in the 1-ring of a corner of T'. So the triangles that can hold an owned sharer i are
  // those of i's 1-ring's vertices and those across their edges: the candidates.
  // Inputs: mesh; x0 (3 per row, owned and ghost) the reference positions; box.
  // Returns what went wrong first (ok: the list is complete).
  PlateProblem build(const HingeMesh &mesh, const double *x0, const ReferenceBox &box);

  // The pass: for each listed triangle and each owned sharer i of its stencil (list order, then
  // stencil order), f_i += F_i / V_i with F = -dE/dy (membrane/curvature.h), block[i] += the
  // Hessian's diagonal block h_ii I / V_i (when block is not null), a third of E / V_i when i is
  // a corner, and its part sum (y_i - y_c0) (x) F_i of the virial. Inputs: p.x (owned and ghost
  // rows), p.volume; outputs: p.f (owned rows).
  void pass(const Particles &p, double **block, const BendingEnergy &energy,
            const Virial &virial) const;

  // The term's part of the stable explicit time step, as bending_stable_steps() for the hinges:
  // by the block Gershgorin theorem over the constant Hessian (blocks h_kl I),
  //   G_i = sum over the listed triangles with i in the stencil, sum_l |h_il| / V_i.
  // Inputs: p.volume, rho (owned rows); dt (owned rows) the estimates so far, +infinity for none.
  // Outputs: dt combined; stiffness (when not null, owned rows, +=) G_i.
  void stable_steps(const Particles &p, const double *rho, double *dt,
                    double *stiffness = nullptr) const;

  // The listed triangles for the assembled stiffness (peri/bond_stiffness.h), made with the
  // list: per triangle its stencil's rows, owners and factors a_k (membrane/curvature.h
  // curvature_factor), so that a_k . a_l = h_kl.
  const PlateCouplings &couplings() const { return couplings_; }

  const std::vector<PlateTriangle> &triangles() const { return list_; }

 private:
  // stencils by triangle: corners in their orientation, the smallest ID first
  std::map<std::array<std::int64_t, 3>, TriangleStencil> cache_;
  // by vertex ID, the triangles whose stencils may hold it (its ring's triangles and those
  // across their edges; the mesh's topology, found once)
  std::map<std::int64_t, std::vector<std::array<std::int64_t, 3>>> around_;
  std::vector<PlateTriangle> list_;
  PlateCouplings couplings_;
  // the list as the pass reads it, in contiguous arrays: per triangle t, its stencil's entries
  // first[t] .. first[t+1]-1 (row, owner, 3 coefficients, h_kk / (A_T D)), A_T D W (9 per
  // triangle) and A_T D (membrane/curvature.h)
  struct PassData {
    std::vector<int> first, row, own;
    std::vector<double> coef, form, adw, scale;
  } flat_;
  void make_couplings();
  void make_pass_data();
};

}    // namespace PeriSISSM

#endif    // PERISISSM_MEMBRANE_PLATE_BENDING_H
