// Test storage for the per-atom arrays of mesh vertices (core mesh/vertex_records.h), laid out
// as fix nosb/mesh allocates them.
#ifndef PERISISSM_TEST_MESH_VERTEX_STORAGE_H
#define PERISISSM_TEST_MESH_VERTEX_STORAGE_H

#include "mesh/vertex_records.h"

#include <array>
#include <vector>

namespace PeriSISSM {

constexpr int kMaxTri = 16;

// nrows rows of the per-atom arrays, as the fix allocates them
template <class Id> struct Storage {
  explicit Storage(int nrows) :
      mesh(nrows, 0), thickness(nrows, 0.0), owntag(nrows, 0), normal_rows(nrows), normal(nrows),
      ntri(nrows, 0), tri_rows(nrows), tri_ptrs(nrows * kMaxTri), tri(nrows)
  {
    for (int i = 0; i < nrows; i++) {
      normal[i] = normal_rows[i].data();
      tri_rows[i].assign(2 * kMaxTri, 0);
      for (int k = 0; k < kMaxTri; k++) tri_ptrs[i * kMaxTri + k] = &tri_rows[i][2 * k];
      tri[i] = &tri_ptrs[i * kMaxTri];
    }
  }
  VertexArrays<Id> arrays()
  {
    return {mesh.data(), thickness.data(), owntag.data(), normal.data(), ntri.data(), tri.data()};
  }
  std::vector<int> mesh;
  std::vector<double> thickness;
  std::vector<Id> owntag;
  std::vector<std::array<double, 3>> normal_rows;
  std::vector<double *> normal;
  std::vector<int> ntri;
  std::vector<std::vector<Id>> tri_rows;
  std::vector<Id *> tri_ptrs;
  std::vector<Id **> tri;
};

}    // namespace PeriSISSM

#endif
