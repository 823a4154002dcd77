/* PERI-SISSM core: building the bond families from the positions of one moment (the reference
   configuration; fix nosb/family, at the first run). The partners of particle i are its
   neighbors j with |x_j - x_i| <= horizon of their types and, when meshes are given, of the
   same mesh (separate layers, a cloth and the body it lies on, are never bonded); stored in the
   order of order_family (peri/family.h), each with its weight (Model::bond_weight, membranes
   with their thickness). Id is the integer type of atom IDs.
*/
#ifndef PERISISSM_PERI_FAMILY_BUILD_H
#define PERISISSM_PERI_FAMILY_BUILD_H

#include "peri/family.h"
#include "peri/family_records.h"
#include "peri/model.h"

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace PeriSISSM {

// Inputs: model; particle i and its neighbors jlist[0..n-1] (local rows, mask applied to each);
//         positions x (3 per row), types, IDs; mesh id per row (null: no meshes).
// Outputs: the partners appended to partners as (ID, local row), in the neighbor list's order.
template <class Id>
void gather_partners(const Model &model, int i, const int *jlist, int n, int mask, const double *x,
                     const int *type, const Id *tag, const int *mesh,
                     std::vector<std::pair<Id, int>> &partners)
{
  for (int jj = 0; jj < n; jj++) {
    const int j = jlist[jj] & mask;
    if (mesh && mesh[i] != mesh[j]) continue;
    const double dx = x[3 * j] - x[3 * i];
    const double dy = x[3 * j + 1] - x[3 * i + 1];
    const double dz = x[3 * j + 2] - x[3 * i + 2];
    const double delta = model.horizon(type[i], type[j]);
    if (dx * dx + dy * dy + dz * dz <= delta * delta) partners.emplace_back(tag[j], j);
  }
}

// Row i takes the partners (ID, local row) as its family: partner IDs, jlocal, omega of each
// reference bond (x0, box), vinit their sum; lamref 0 and owntag ownid.
// Inputs: types, volumes vfrac, thickness per row (null: no membranes).
// Returns the first slot whose partner is at the position of particle i (reference bond of
// length 0; the slots from it on are not stored), -1 if none.
template <class Id>
int store_family(const Model &model, const FamilyArrays<Id> &a, int i, Id ownid,
                 const std::vector<std::pair<Id, int>> &partners, const double *x0,
                 const ReferenceBox &box, const int *type, const double *vfrac,
                 const double *thickness)
{
  a.npartner[i] = (int) partners.size();
  a.vinit[i] = 0.0;
  a.lamref[i] = 0.0;
  a.owntag[i] = ownid;
  for (int b = 0; b < a.npartner[i]; b++) {
    const int j = partners[b].second;
    double xi[3];
    reference_bond(x0, box, i, j, xi);
    const double r = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
    if (r == 0.0) return b;
    a.omega[i][b] = thickness
        ? model.bond_weight(r, type[i], type[j], vfrac[i], vfrac[j], thickness[i], thickness[j])
        : model.bond_weight(r, type[i], type[j], vfrac[i], vfrac[j]);
    a.partner[i][b] = partners[b].first;
    a.jlocal[i][b] = j;
    a.vinit[i] += a.omega[i][b];
  }
  return -1;
}

// Rows 0..n-1 (n = fam.size()) take the partners fam[i] as their families (store_family) and
// their shape tensors (update_shape through view, with the reference normals of model).
// Inputs: IDs tag, x0, box, types, volumes vfrac, thicknesses (null: no membranes).
// Outputs: bonds (slots stored) and singular (rows with a singular K) are added to.
// Returns (-1, -1), or at the first row with a partner at its position (store_family) that row
// and the partner's local row (the rows after it are not stored).
template <class Id>
std::pair<int, int>
store_families(const Model &model, const FamilyArrays<Id> &a, const Families &view,
               const std::vector<std::vector<std::pair<Id, int>>> &fam, const Id *tag,
               const double *x0, const ReferenceBox &box, const int *type, const double *vfrac,
               const double *thickness, int64_t &bonds, int64_t &singular)
{
  for (int i = 0; i < (int) fam.size(); i++) {
    const int b = store_family(model, a, i, tag[i], fam[i], x0, box, type, vfrac, thickness);
    if (b >= 0) return {i, fam[i][b].second};
    update_shape(view, x0, box, i, model.reference_normal(view, type[i], i));
    bonds += a.npartner[i];
    if (!a.kregular[i]) singular++;
  }
  return {-1, -1};
}

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FAMILY_BUILD_H
