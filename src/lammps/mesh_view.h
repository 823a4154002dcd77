/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   What the styles that use the meshes of read_mesh (pair peri/nosb's membranes and bending,
   the bond-family fix, fix nosb/contact) read of them, per local atom (owned and ghost rows, as
   atom->x). fix nosb/mesh keeps the data and implements it; the readers see nothing else of
   it. The arrays are its per-atom arrays: a pointer taken from them is valid until they grow.
------------------------------------------------------------------------- */

#ifndef LMP_PERISISSM_MESH_VIEW_H
#define LMP_PERISISSM_MESH_VIEW_H

#include "lmptype.h"

namespace LAMMPS_NS {

class MeshView {
 public:
  // the deck's meshes, nullptr if it has none (a lookup: it defines and deletes no fix)
  static MeshView *find(class LAMMPS *);
  // find(); after read_restart, the meshes of the restart file when the deck has not defined
  // fix nosb/mesh again (defined then as NOSB_MESH: doc/read_mesh.rst). Collective.
  static MeshView *restore(class LAMMPS *);

  // mesh id of atom i, 0 if it is no mesh vertex
  int mesh_of(int i) const { return mesh[i]; }
  // thickness of the mesh of atom i (0 for non-mesh atoms)
  double thickness_of(int i) const { return thickness[i]; }
  // number of triangles at atom i
  int ntri_of(int i) const { return ntri[i]; }
  // ID of corner c (0 or 1) of triangle k of atom i: (i, corner 0, corner 1) is the
  // triangle's orientation
  tagint corner_of(int i, int k, int c) const { return tri[i][k][c]; }
  // the per-atom arrays of mesh ids and thicknesses
  const int *mesh_ids() const { return mesh; }
  const double *thicknesses() const { return thickness; }
  // reference unit normals (3 per row; zero until set, and for non-mesh atoms)
  double **reference_normals() const { return normal0; }

  // reference normals := the angle-weighted vertex normals of the current positions (owned
  // and ghost rows). Collective.
  virtual void set_reference_normals() = 0;

 protected:
  ~MeshView() = default;

  int *mesh = nullptr;            // mesh id of the atom, 0 = not a mesh vertex
  double *thickness = nullptr;    // thickness of its mesh, 0 for non-mesh atoms
  int *ntri = nullptr;           // number of triangles at the atom (at most fix nosb/mesh's MAXTRI)
  tagint ***tri = nullptr;       // tri[i][k][0], tri[i][k][1]: IDs of the other two vertices of
                                 //   triangle k of atom i, in the triangle's orientation
  double **normal0 = nullptr;    // reference unit normal; 0 until set
};

}    // namespace LAMMPS_NS

#endif
