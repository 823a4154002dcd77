/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, the bending term of membranes (pair_coeff ... bend D|auto).

   The hinges are the interior edges of the meshes read with read_mesh (fix nosb/mesh): an edge
   (x0, x1) with the third vertices x2 of its triangle (x0, x1, x2) and x3 of (x1, x0, x3). The
   energy c (theta - theta0)^2 and its derivatives are the core's (membrane/hinge.h). Every
   owned vertex evaluates the hinges it belongs to (as an edge's end: the edges (i, a) of its
   triangles; as a third vertex: the edge (a, b) opposite it in each of its triangles, whose other
   triangle is in a's list) and keeps its own share: its force, its diagonal block, a quarter of
   the energy and its part of the virial. Each hinge is thus evaluated by its four vertices and
   no force goes to a ghost atom (no reverse communication); a vertex sees the others as owned or
   ghost atoms (the ghost cutoff covers the mesh's edges: read_mesh checks it).
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"
#include "fix_nosb_mesh.h"

#include "membrane/hinge.h"
#include "peri/model.h"

#include "atom.h"
#include "domain.h"
#include "error.h"

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
   the hinges of every owned vertex of a type with bending (compute(): forces, energy density,
   virial, blocks)
------------------------------------------------------------------------- */

void PairPeriNosb::compute_bending()
{
  double **x = atom->x;
  double **x0 = atom->x0;
  double **f = atom->f;
  const double *vfrac = atom->vfrac;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int *mesh = meshfix->mesh;
  const int *ntri = meshfix->ntri;
  tagint ***tri = meshfix->tri;
  const PeriSISSM::ReferenceBox &box = family->box;

  // local index of vertex tag seen from atom i (its closest image), -1 if not here
  auto vertex = [&](int i, tagint tag) {
    const int j = atom->map(tag);
    return j < 0 ? -1 : domain->closest_image(i, j);
  };
  tagint missing = 0;

  // one hinge (v[0], v[1] | v[2], v[3]) of owned atom i, which is vertex `me` of it
  auto hinge = [&](int i, const int v[4], int me) {
    for (int k = 0; k < 4; k++)
      if (v[k] < 0) return false;
    const double D = 0.5 * (bending_modulus(v[0]) + bending_modulus(v[1]));
    if (D <= 0.0) return true;
    // reference positions relative to i (minimum image in the box of the families)
    double X[4][3];
    for (int k = 0; k < 4; k++) {
      for (int d = 0; d < 3; d++) X[k][d] = x0[v[k]][d] - x0[i][d];
      if (box.any()) box.image(X[k][0], X[k][1], X[k][2]);
    }
    const double c = PeriSISSM::hinge_stiffness(D, X[0], X[1], X[2], X[3]);
    const double theta0 = PeriSISSM::hinge_angle(X[0], X[1], X[2], X[3]);
    double force[4][3], blk[4][6];
    const double E = PeriSISSM::hinge_energy(x[v[0]], x[v[1]], x[v[2]], x[v[3]], theta0, c,
                                             force, block_rows ? blk : nullptr);
    const double vi = vfrac[i];
    for (int d = 0; d < 3; d++) f[i][d] += force[me][d] / vi;
    if (block_rows)
      for (int k = 0; k < 6; k++) block_rows[i][k] += blk[me][k] / vi;
    if (eflag_either) {
      const double e = 0.25 * E / vi;
      if (eflag_global) eng_vdwl += e;
      if (eflag_atom) eatom[i] += e;
    }
    if (vflag_either) {
      // this vertex's part of sum_v (x_v - x_0) (x) F_v (translation invariant: sum_v F_v = 0)
      double r[3];
      for (int d = 0; d < 3; d++) r[d] = x[i][d] - x[v[0]][d];
      const double *F = force[me];
      const double w[6] = {r[0] * F[0], r[1] * F[1], r[2] * F[2],
                           r[0] * F[1], r[0] * F[2], r[1] * F[2]};
      if (vflag_global)
        for (int k = 0; k < 6; k++) virial[k] += w[k];
      if (vflag_atom)
        for (int k = 0; k < 6; k++) vatom[i][k] += w[k];
    }
    return true;
  };

  for (int i = 0; i < nlocal; i++) {
    if (!mesh[i] || bend[type[i]] == 0.0) continue;
    const tagint itag = atom->tag[i];
    for (int k = 0; k < ntri[i]; k++) {
      const tagint a = tri[i][k][0], b = tri[i][k][1];
      // the edge (i, a): triangles (i, a, b) and (a, i, c) = i's (i, c, a)
      for (int k2 = 0; k2 < ntri[i]; k2++) {
        if (tri[i][k2][1] != a) continue;
        const int v[4] = {i, vertex(i, a), vertex(i, b), vertex(i, tri[i][k2][0])};
        if (!hinge(i, v, 0)) missing = itag;
        break;
      }
      // the edge (a, b) opposite i: triangles (a, b, i) and (b, a, d) = a's (a, d, b)
      const int ja = vertex(i, a);
      if (ja < 0) {
        missing = itag;
        continue;
      }
      for (int k2 = 0; k2 < ntri[ja]; k2++) {
        if (tri[ja][k2][1] != b) continue;
        const int v[4] = {ja, vertex(i, b), i, vertex(i, tri[ja][k2][0])};
        if (!hinge(i, v, 2)) missing = itag;
        break;
      }
    }
  }
  if (missing)
    error->one(FLERR,
               "Pair peri/nosb bend: a vertex of a hinge of atom {} is neither owned nor a ghost "
               "atom here: the ghost cutoff is shorter than two edges of its mesh (comm_modify "
               "cutoff)",
               missing);
}
