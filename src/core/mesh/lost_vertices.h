/* PERI-SISSM core: triangles that lost a vertex (fix nosb/mesh at every init: after
   delete_atoms or lost atoms, a triangle whose other vertex no longer exists as an atom of the
   same mesh is dropped by the vertices that still have it).

   A rank checks the corners it holds as local atoms (owned or ghost rows) itself; the others
   are asked of all ranks as (ID, mesh id) pairs through the caller's function, which answers
   with owned_vertices() on every rank and combines the answers (the communication).
*/
#ifndef PERISISSM_MESH_LOST_VERTICES_H
#define PERISISSM_MESH_LOST_VERTICES_H

#include "mesh/vertex_records.h"

#include <vector>

namespace PeriSISSM {

// For the (ID, mesh id) pairs (flattened: id0, mesh0, id1, mesh1, ...): 1 where the ID is an
// owned atom (row local(id) in 0..nlocal-1) of that mesh, else 0.
// Inputs: pairs, nlocal, local (ID -> row, -1 if none), mesh (mesh id per row).
template <class Id, class Local>
std::vector<int> owned_vertices(const std::vector<Id> &pairs, int nlocal, Local local,
                                const int *mesh)
{
  const int npairs = (int) pairs.size() / 2;
  std::vector<int> here(npairs, 0);
  for (int k = 0; k < npairs; k++) {
    const int j = local(pairs[2 * k]);
    if (j >= 0 && j < nlocal && mesh[j] == (int) pairs[2 * k + 1]) here[k] = 1;
  }
  return here;
}

// The triangles of the owned mesh rows 0..nlocal-1 keep (in their order) only those whose two
// other vertices are atoms of the row's mesh: a corner with a local row (local(id) >= 0) is
// checked there; the others are collected as (ID, mesh id) pairs in the order of the rows,
// triangles and corners and passed to exists_elsewhere(pairs), which returns one flag per pair
// (nonzero: an atom with that ID and mesh id exists on some rank). exists_elsewhere is called
// exactly once, with no pairs too (it may communicate).
// Inputs: a, nlocal, local (ID -> row, -1 if none), exists_elsewhere.
// Outputs: the triangle lists of the rows (ntri, tri).
template <class Id, class Local, class ExistsElsewhere>
void drop_lost_triangles(const VertexArrays<Id> &a, int nlocal, Local local,
                         ExistsElsewhere exists_elsewhere)
{
  std::vector<Id> wanted;
  std::vector<Id *> where;
  for (int i = 0; i < nlocal; i++) {
    if (!a.mesh[i]) continue;
    for (int k = 0; k < a.ntri[i]; k++) {
      for (int c = 0; c < 2; c++) {
        const int j = local(a.tri[i][k][c]);
        if (j >= 0) {
          if (a.mesh[j] != a.mesh[i]) a.tri[i][k][c] = 0;
        } else {
          wanted.push_back(a.tri[i][k][c]);
          wanted.push_back(a.mesh[i]);
          where.push_back(&a.tri[i][k][c]);
        }
      }
    }
  }
  const std::vector<int> exists = exists_elsewhere(wanted);
  for (size_t k = 0; k < where.size(); k++)
    if (!exists[k]) *where[k] = 0;
  for (int i = 0; i < nlocal; i++)
    if (a.mesh[i]) keep_complete_triangles(a, i);
}

}    // namespace PeriSISSM

#endif
