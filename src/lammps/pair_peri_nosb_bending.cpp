/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, the bending term of membranes (pair_coeff ... bend D|auto).

   The hinges are the interior edges of the meshes read with read_mesh (fix nosb/mesh): an edge
   (x0, x1) with the third vertices x2 of its triangle (x0, x1, x2) and x3 of (x1, x0, x3). The
   energy c (theta - theta0)^2 and its derivatives are the core's (membrane/hinge.h). Each rank
   keeps a list of the hinges with at least one owned vertex, each hinge once, with its rest
   angle and stiffness; it is built again only after a neighbor list build (atoms migrated or
   were sorted) or a new run's init, since evaluating the hinges is cheap next to finding their
   vertices and rest shape. A force evaluation evaluates every hinge of the list once and gives
   each of its owned vertices its own share: its force, its diagonal block, a quarter of the
   energy and its part of the virial. A hinge that straddles ranks is evaluated on each of them
   and no force goes to a ghost atom (no reverse communication); its other vertices are ghost
   atoms (the ghost cutoff covers the mesh's edges: read_mesh checks it).
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"
#include "fix_nosb_mesh.h"

#include "membrane/hinge.h"
#include "peri/bond_stiffness.h"
#include "peri/model.h"

#include "atom.h"
#include "domain.h"
#include "error.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   bending modulus of atom i (owned or ghost): the type's D, or with bend auto
   E t^3 / (12 (1 - nu^2)) from its material and its mesh's thickness; 0 without bending
------------------------------------------------------------------------- */

double PairPeriNosb::bending_modulus(int i) const
{
  const int t = atom->type[i];
  const double b = bend[t];
  if (b >= 0.0) return b;
  const double thick = meshfix->thickness[i];
  return bend_auto_factor[t] * thick * thick * thick;
}

/* ----------------------------------------------------------------------
   the hinge list of this rank (compute_bending(), when stale). Every owned vertex of a type with
   bending finds the hinges it belongs to, each once (as an edge's end: the edges (i, a) of its
   triangles; as a third vertex: the edge (a, b) opposite it in each of its triangles, whose
   other triangle is in a's list), with the other vertices at their images closest to it. The
   smallest of a hinge's owned vertices keeps it, so that it is listed once, with its edge
   running from the smaller tag to the larger (one vertex order wherever it is found); theta0
   and c come from the reference positions relative to the edge's first vertex, in the box of
   the families.
------------------------------------------------------------------------- */

void PairPeriNosb::build_hinges()
{
  double **x0 = atom->x0;
  const tagint *tag = atom->tag;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int *mesh = meshfix->mesh;
  const int *ntri = meshfix->ntri;
  tagint ***tri = meshfix->tri;
  const PeriSISSM::ReferenceBox &box = family->box;

  // local index of vertex tag seen from atom i (its closest image), -1 if not here
  auto vertex = [&](int i, tagint t) {
    const int j = atom->map(t);
    return j < 0 ? -1 : domain->closest_image(i, j);
  };
  // the owned vertices that take a share of their hinges: those of a type with bending (as
  // when each vertex evaluated its own hinges: one of a type without takes no share even of a
  // hinge whose edge's ends give it a modulus)
  auto sharing = [&](int j) { return j >= 0 && j < nlocal && mesh[j] && bend[type[j]] != 0.0; };
  tagint missing = 0;
  hinges.clear();

  // the hinge (w[0], w[1] | w[2], w[3]) found by owned atom i; false if a vertex is not here
  auto add = [&](int i, const int w[4]) {
    for (int k = 0; k < 4; k++)
      if (w[k] < 0) return false;
    // the edge from its smaller tag, the same hinge as (w[1], w[0] | w[3], w[2])
    const bool flip = tag[w[0]] > tag[w[1]];
    const int v[4] = {w[flip], w[!flip], w[2 + flip], w[2 + !flip]};
    Hinge h;
    for (int k = 0; k < 4; k++) {
      h.v[k] = v[k];
      // the owned atom itself, also where its closest image to i is a periodic ghost
      const int j = atom->map(tag[v[k]]);
      h.own[k] = sharing(j) ? j : -1;
      if (h.own[k] >= 0 && h.own[k] < i) return true;    // listed by that smaller vertex
    }
    const double D = 0.5 * (bending_modulus(v[0]) + bending_modulus(v[1]));
    if (D <= 0.0) return true;
    // reference positions relative to x0 (minimum image in the box of the families)
    double X[4][3];
    for (int k = 0; k < 4; k++) {
      for (int d = 0; d < 3; d++) X[k][d] = x0[v[k]][d] - x0[v[0]][d];
      if (box.any()) box.image(X[k][0], X[k][1], X[k][2]);
    }
    h.c = PeriSISSM::hinge_stiffness(D, X[0], X[1], X[2], X[3]);
    h.theta0 = PeriSISSM::hinge_angle(X[0], X[1], X[2], X[3]);
    hinges.push_back(h);
    return true;
  };

  for (int i = 0; i < nlocal; i++) {
    if (!sharing(i)) continue;
    for (int k = 0; k < ntri[i]; k++) {
      const tagint a = tri[i][k][0], b = tri[i][k][1];
      // the edge (i, a): triangles (i, a, b) and (a, i, c) = i's (i, c, a)
      for (int k2 = 0; k2 < ntri[i]; k2++) {
        if (tri[i][k2][1] != a) continue;
        const int v[4] = {i, vertex(i, a), vertex(i, b), vertex(i, tri[i][k2][0])};
        if (!add(i, v)) missing = tag[i];
        break;
      }
      // the edge (a, b) opposite i: triangles (a, b, i) and (b, a, d) = a's (a, d, b)
      const int ja = vertex(i, a);
      if (ja < 0) {
        missing = tag[i];
        continue;
      }
      for (int k2 = 0; k2 < ntri[ja]; k2++) {
        if (tri[ja][k2][1] != b) continue;
        const int v[4] = {ja, vertex(i, b), i, vertex(i, tri[ja][k2][0])};
        if (!add(i, v)) missing = tag[i];
        break;
      }
    }
  }
  // in the order of their edges' tags: a vertex then sums its hinges' forces in the same order
  // however the atoms are ordered locally or split between ranks, and a run continued from a
  // restart file (whose atoms are sorted anew) gets the same bending forces to the last bit
  std::sort(hinges.begin(), hinges.end(), [tag](const Hinge &p, const Hinge &q) {
    return tag[p.v[0]] != tag[q.v[0]] ? tag[p.v[0]] < tag[q.v[0]] : tag[p.v[1]] < tag[q.v[1]];
  });
  if (missing)
    error->one(FLERR,
               "Pair peri/nosb bend: a vertex of a hinge of atom {} is neither owned nor a ghost "
               "atom here: the ghost cutoff is shorter than two edges of its mesh (comm_modify "
               "cutoff)",
               missing);
  hinges_stale = 0;
}

/* ----------------------------------------------------------------------
   the hinges of this rank's list, each evaluated once (compute(): forces, energy density,
   virial, blocks of its owned vertices)
------------------------------------------------------------------------- */

void PairPeriNosb::compute_bending()
{
  if (hinges_stale) build_hinges();
  double **x = atom->x;
  double **f = atom->f;
  const double *vfrac = atom->vfrac;

  for (const Hinge &h : hinges) {
    const int *v = h.v;
    double force[4][3], blk[4][6];
    const double E = PeriSISSM::hinge_energy(x[v[0]], x[v[1]], x[v[2]], x[v[3]], h.theta0, h.c,
                                             force, block_rows ? blk : nullptr);
    for (int k = 0; k < 4; k++) {
      const int i = h.own[k];
      if (i < 0) continue;
      const double vi = vfrac[i];
      for (int d = 0; d < 3; d++) f[i][d] += force[k][d] / vi;
      if (block_rows)
        for (int m = 0; m < 6; m++) block_rows[i][m] += blk[k][m] / vi;
      if (eflag_either) {
        const double e = 0.25 * E / vi;
        if (eflag_global) eng_vdwl += e;
        if (eflag_atom) eatom[i] += e;
      }
      if (vflag_either) {
        // this vertex's part of sum_v (x_v - x_0) (x) F_v (translation invariant: sum_v F_v = 0)
        double r[3];
        for (int d = 0; d < 3; d++) r[d] = x[v[k]][d] - x[v[0]][d];
        const double *F = force[k];
        const double w[6] = {r[0] * F[0], r[1] * F[1], r[2] * F[2],
                             r[0] * F[1], r[0] * F[2], r[1] * F[2]};
        if (vflag_global)
          for (int m = 0; m < 6; m++) virial[m] += w[m];
        if (vflag_atom)
          for (int m = 0; m < 6; m++) vatom[i][m] += w[m];
      }
    }
  }
}

/* ----------------------------------------------------------------------
   ImplicitForces: the hinges of this rank's list in the current positions, for the coarse
   level's matrix (each hinge once; a vertex's row is where compute_bending() puts its share)
------------------------------------------------------------------------- */

void PairPeriNosb::hinge_couplings(PeriSISSM::HingeCouplings &couplings, bool gradients)
{
  couplings.vertex.clear();
  couplings.row.clear();
  couplings.grad.clear();
  if (!any_bend || !meshfix) return;
  if (hinges_stale) build_hinges();
  double **x = atom->x;
  for (const Hinge &h : hinges) {
    const int *v = h.v;
    for (int k = 0; k < 4; k++) {
      couplings.vertex.push_back(v[k]);
      couplings.row.push_back(h.own[k]);
    }
    if (!gradients) continue;
    double g[4][3];
    PeriSISSM::hinge_angle(x[v[0]], x[v[1]], x[v[2]], x[v[3]], g);
    const double s = std::sqrt(2.0 * h.c);
    for (int k = 0; k < 4; k++)
      for (int d = 0; d < 3; d++) couplings.grad.push_back(s * g[k][d]);
  }
}
