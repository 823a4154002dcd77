/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/mesh: the triangles of the meshes read by read_mesh (created by the first read_mesh
   as "NOSB_MESH all nosb/mesh"; users define it only to read a data file's mesh triangles back,
   or to re-specify it after read_restart: doc/read_mesh.rst).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(nosb/mesh,FixNosbMesh);
// clang-format on
#else

#ifndef LMP_FIX_NOSB_MESH_H
#define LMP_FIX_NOSB_MESH_H

#include "fix.h"
#include "mesh_view.h"

#include "mesh/data_triangles.h"

namespace LAMMPS_NS {

class FixNosbMesh : public Fix, public MeshView {
 public:
  // largest number of triangles at a vertex (the per-atom storage; read_mesh refuses more)
  static constexpr int MAXTRI = 16;
  // the ID read_mesh gives the fix
  static constexpr const char *DEFAULT_ID = "NOSB_MESH";

  FixNosbMesh(class LAMMPS *, int, char **);
  ~FixNosbMesh() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void min_setup(int) override;
  int modify_param(int, char **) override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_border(int, int *, double *) override;
  int unpack_border(int, int, double *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  void write_data_header(FILE *, int) override;
  void write_data_section_size(int, int &, int &) override;
  void write_data_section_pack(int, double **) override;
  void write_data_section_keyword(int, FILE *) override;
  void write_data_section(int, FILE *, int, double **, int) override;
  void read_data_header(char *) override;
  void read_data_section(char *, int, char *, tagint) override;
  bigint read_data_skip_lines(char *) override;

  // the deck's mesh fix, nullptr if none (a lookup: it defines and deletes no fix)
  static FixNosbMesh *find(class LAMMPS *);
  // find(); if the deck has none but the restart file read last holds one as NOSB_MESH (LAMMPS
  // keeps its data until the first run or init), define it again and return it (MeshView's
  // restore: pair peri/nosb's init calls it before the fixes' init).
  static FixNosbMesh *restore(class LAMMPS *);

  // angle-weighted unit vertex normal (core mesh/mesh_geometry.h) of every owned mesh atom, the
  // other vertices looked up by ID with atom->map, each at its image closest to x_i; n[i] = 0
  // for non-mesh atoms. Collective: a vertex that is neither owned nor a ghost on a rank is an
  // error on all ranks naming the atom and the vertex (the ghost cutoff is shorter than the
  // mesh's edges). Inputs: x (nlocal + nghost rows, as atom->x). Outputs: n (nlocal rows).
  void vertex_normals(double **x, double **n);
  // normal0 := vertex_normals(atom->x) (collective; called when the bond families are built)
  void set_reference_normals() override;

  // read_mesh: a new mesh of ntriangles triangles; returns its mesh id (1, 2, ...)
  int add_mesh(bigint ntriangles_added);
  // read_mesh: owned atom i is a vertex of mesh id with thickness t, in the n triangles
  // (i, others[k][0], others[k][1]) (n <= MAXTRI)
  void set_vertex(int i, int id, double t, int n, const tagint (*others)[2]);

  // state (the per-atom arrays are MeshView's: mesh, thickness, ntri, tri, normal0)
  int nmesh;            // number of meshes read (mesh ids are 1..nmesh)
  bigint ntriangles;    // number of triangles of all meshes (all ranks)

 protected:
  tagint *owntag;          // the atom's ID when its triangles were stored (detects renumbering)
  double **output;         // per-atom array: mesh, thickness, ntri, normal0 x y z (owned rows)
  int normals_at_setup;    // fix_modify normals yes: set missing normal0 at each run's setup
  PeriSISSM::DataSectionRead data;    // read_data: the read of the section under way

  PeriSISSM::VertexArrays<tagint> rows() const;    // the per-atom arrays (core mesh/)
  void refresh_output(int i);
  int local_index(tagint) const;
  void check_ids();
  void drop_lost_triangles();
  int owned_triangles() const;    // triangles this rank writes (writes_triangle)
  void normals_where_missing();
};

}    // namespace LAMMPS_NS

#endif
#endif
