/* PERI-SISSM core: the per-atom records of a triangle-mesh vertex as fix nosb/mesh keeps them:
   mesh id, thickness, the atom's own ID when its triangles were stored, reference normal, and
   the triangles at the vertex (each as the IDs of its other two vertices in the triangle's
   orientation). Rows of the arrays are atoms; Id is the integer type of atom IDs (LAMMPS's
   tagint: int or int64_t).

   Buffers of doubles carry an ID as the bit pattern of its value as a 64-bit integer (as
   LAMMPS's ubuf does), so that any ID survives exactly.

   Exchange and restart record (pack_vertex, VertexRecord::kExchange): mesh id; for a mesh
   vertex then thickness, owntag, normal (3), ntri and the 2 x ntri IDs of the triangles.
   Border record (VertexRecord::kBorder, ghosts): the same without owntag (ghosts do not check
   renumbering).
*/
#ifndef PERISISSM_MESH_VERTEX_RECORDS_H
#define PERISISSM_MESH_VERTEX_RECORDS_H

#include "linalg/id_bits.h"

namespace PeriSISSM {

// the two records of a vertex: exchange and restart (with owntag), border (ghosts: without)
enum class VertexRecord { kExchange, kBorder };

// doubles of a mesh vertex's exchange record before its triangles
constexpr int kVertexScalars = 7;
// doubles of a mesh vertex's border record before its triangles
constexpr int kVertexBorderScalars = kVertexScalars - 1;

// the rows of the per-atom arrays (owned and ghost atoms)
template <class Id> struct VertexArrays {
  int *mesh;            // mesh id, 0 = not a mesh vertex
  double *thickness;    // thickness of the atom's mesh, 0 for other atoms
  Id *owntag;           // the atom's ID when its triangles were stored
  double **normal0;     // reference unit normal (3 per row)
  int *ntri;            // triangles at the atom
  Id ***tri;            // tri[i][k][0..1]: the other two vertices of triangle k of atom i
};

// doubles of the exchange record of a vertex with ntri triangles (1 for a non-mesh atom)
inline int vertex_record_size(int mesh, int ntri)
{
  return mesh ? kVertexScalars + 2 * ntri : 1;
}

// Row i is no mesh vertex: mesh id, thickness, triangles and normal zero; owntag zero unless
// keep_owntag.
template <class Id> void clear_vertex(const VertexArrays<Id> &a, int i, bool keep_owntag = false)
{
  a.mesh[i] = 0;
  a.thickness[i] = 0.0;
  a.ntri[i] = 0;
  a.normal0[i][0] = a.normal0[i][1] = a.normal0[i][2] = 0.0;
  if (!keep_owntag) a.owntag[i] = 0;
}

// row j := row i
template <class Id> void copy_vertex(const VertexArrays<Id> &a, int i, int j)
{
  a.mesh[j] = a.mesh[i];
  a.thickness[j] = a.thickness[i];
  a.ntri[j] = a.ntri[i];
  for (int k = 0; k < a.ntri[i]; k++) {
    a.tri[j][k][0] = a.tri[i][k][0];
    a.tri[j][k][1] = a.tri[i][k][1];
  }
  for (int d = 0; d < 3; d++) a.normal0[j][d] = a.normal0[i][d];
  a.owntag[j] = a.owntag[i];
}

// Inputs: row i, the record kind. Outputs: its record in buf. Returns the doubles written.
template <class Id>
int pack_vertex(const VertexArrays<Id> &a, int i, double *buf,
                VertexRecord kind = VertexRecord::kExchange)
{
  int m = 0;
  buf[m++] = a.mesh[i];
  if (!a.mesh[i]) return m;
  buf[m++] = a.thickness[i];
  if (kind == VertexRecord::kExchange) buf[m++] = id_bits(a.owntag[i]);
  for (int d = 0; d < 3; d++) buf[m++] = a.normal0[i][d];
  buf[m++] = a.ntri[i];
  for (int k = 0; k < a.ntri[i]; k++) {
    buf[m++] = id_bits(a.tri[i][k][0]);
    buf[m++] = id_bits(a.tri[i][k][1]);
  }
  return m;
}

// Inputs: a record of the given kind in buf. Outputs: row i (a border record leaves its
// owntag as it is). Returns the doubles read.
template <class Id>
int unpack_vertex(const VertexArrays<Id> &a, int i, const double *buf,
                  VertexRecord kind = VertexRecord::kExchange)
{
  const bool exchange = kind == VertexRecord::kExchange;
  int m = 0;
  const int mesh = static_cast<int>(buf[m++]);
  if (!mesh) {
    clear_vertex(a, i, !exchange);
    return m;
  }
  a.mesh[i] = mesh;
  a.thickness[i] = buf[m++];
  if (exchange) a.owntag[i] = bits_id<Id>(buf[m++]);
  for (int d = 0; d < 3; d++) a.normal0[i][d] = buf[m++];
  a.ntri[i] = static_cast<int>(buf[m++]);
  for (int k = 0; k < a.ntri[i]; k++) {
    a.tri[i][k][0] = bits_id<Id>(buf[m++]);
    a.tri[i][k][1] = bits_id<Id>(buf[m++]);
  }
  return m;
}

// pack_vertex of the rows list[0..n-1], one record after the other. Returns the doubles written.
template <class Id>
int pack_vertices(const VertexArrays<Id> &a, int n, const int *list, double *buf, VertexRecord kind)
{
  int m = 0;
  for (int l = 0; l < n; l++) m += pack_vertex(a, list[l], &buf[m], kind);
  return m;
}

// unpack_vertex of n records into the rows first..first+n-1. Returns the doubles read.
template <class Id>
int unpack_vertices(const VertexArrays<Id> &a, int n, int first, const double *buf,
                    VertexRecord kind)
{
  int m = 0;
  for (int i = first; i < first + n; i++) m += unpack_vertex(a, i, &buf[m], kind);
  return m;
}

// Row i keeps, in their order, the triangles whose other two vertices are both set (an ID 0
// marks a vertex that no longer exists). Returns the number kept (= ntri[i]).
template <class Id> int keep_complete_triangles(const VertexArrays<Id> &a, int i)
{
  int n = 0;
  for (int k = 0; k < a.ntri[i]; k++) {
    if (a.tri[i][k][0] == 0 || a.tri[i][k][1] == 0) continue;
    a.tri[i][n][0] = a.tri[i][k][0];
    a.tri[i][n][1] = a.tri[i][k][1];
    n++;
  }
  a.ntri[i] = n;
  return n;
}

// Row i is a mesh vertex without a reference normal (all three components zero).
template <class Id> bool lacks_normal(const VertexArrays<Id> &a, int i)
{
  return a.mesh[i] && a.normal0[i][0] == 0.0 && a.normal0[i][1] == 0.0 && a.normal0[i][2] == 0.0;
}

// Of rows 0..nrows-1, those that lack a normal get n[i]. Returns the rows set.
template <class Id> int fill_missing_normals(const VertexArrays<Id> &a, int nrows, double *const *n)
{
  int nset = 0;
  for (int i = 0; i < nrows; i++) {
    if (!lacks_normal(a, i)) continue;
    for (int d = 0; d < 3; d++) a.normal0[i][d] = n[i][d];
    nset++;
  }
  return nset;
}

// A triangle is written (and counted) once, by its vertex with the smallest ID: true for the
// vertex me of triangle (me, a, b).
template <class Id> bool writes_triangle(Id me, Id a, Id b)
{
  return me < a && me < b;
}

// The triangles rows 0..nrows-1 (IDs tag) write (writes_triangle). Returns their number.
template <class Id> int count_written_triangles(const VertexArrays<Id> &a, int nrows, const Id *tag)
{
  int n = 0;
  for (int i = 0; i < nrows; i++)
    if (a.mesh[i])
      for (int k = 0; k < a.ntri[i]; k++)
        n += writes_triangle(tag[i], a.tri[i][k][0], a.tri[i][k][1]);
  return n;
}

// The triangles rows 0..nrows-1 (IDs tag) write, in the order of the rows and their triangles,
// one row of buf each: mesh id, thickness and the three vertex IDs (id_bits) from the writing
// vertex on in the triangle's orientation. Returns the rows of buf filled.
template <class Id>
int pack_written_triangles(const VertexArrays<Id> &a, int nrows, const Id *tag, double *const *buf)
{
  int n = 0;
  for (int i = 0; i < nrows; i++) {
    if (!a.mesh[i]) continue;
    for (int k = 0; k < a.ntri[i]; k++) {
      if (!writes_triangle(tag[i], a.tri[i][k][0], a.tri[i][k][1])) continue;
      buf[n][0] = a.mesh[i];
      buf[n][1] = a.thickness[i];
      buf[n][2] = id_bits(tag[i]);
      buf[n][3] = id_bits(a.tri[i][k][0]);
      buf[n][4] = id_bits(a.tri[i][k][1]);
      n++;
    }
  }
  return n;
}

// values of a row of fix nosb/mesh's per-atom output: mesh id, thickness, ntri, normal0
constexpr int kVertexOutputs = 6;
// Inputs: row i. Outputs: out (kVertexOutputs values).
template <class Id> void output_row(const VertexArrays<Id> &a, int i, double *out)
{
  out[0] = a.mesh[i];
  out[1] = a.thickness[i];
  out[2] = a.ntri[i];
  for (int d = 0; d < 3; d++) out[3 + d] = a.normal0[i][d];
}

// Row i gets triangle v (three vertex IDs in the triangle's orientation) in which it is corner
// c (v[c] is the atom): stored rotated to start at it, as (v[c+1], v[c+2]). Returns false (and
// stores nothing) when row i has maxtri triangles already.
template <class Id>
bool add_corner(const VertexArrays<Id> &a, int i, const Id v[3], int c, int maxtri)
{
  if (a.ntri[i] >= maxtri) return false;
  a.tri[i][a.ntri[i]][0] = v[(c + 1) % 3];
  a.tri[i][a.ntri[i]][1] = v[(c + 2) % 3];
  a.ntri[i]++;
  return true;
}

}    // namespace PeriSISSM

#endif
