/* PERI-SISSM core: a mesh file placed in the box (see place_mesh.h). */
#include "mesh/place_mesh.h"

namespace PeriSISSM {

PlacedMesh place_mesh(const TriangleMesh &mesh, const Placement &placement)
{
  PlacedMesh placed;
  placed.x.resize(mesh.vertices.size());
  for (size_t k = 0; k < mesh.vertices.size(); k++)
    place(placement, mesh.vertices[k].data(), placed.x[k].data());
  placed.area = vertex_areas(placed.x, mesh.triangles);
  for (const auto &t : mesh.triangles)
    placed.total_area +=
        triangle_area(placed.x[t[0]].data(), placed.x[t[1]].data(), placed.x[t[2]].data());
  return placed;
}

SubdomainVertices subdomain_vertices(const MeshBox &box, std::vector<std::array<double, 3>> &c)
{
  SubdomainVertices result;
  for (int k = 0; k < (int) c.size(); k++) {
    bool inside = true;
    for (int d = 0; d < 3; d++) {
      int side = 0;
      const BoxFit fit =
          fit_to_box(c[k][d], box.lo[d], box.hi[d], box.periodic[d], box.fixed[d], side);
      if (fit == BoxFit::kOutside) {
        result.outside = k;
        result.dim = d;
        result.side = side;
        return result;
      }
      if (fit == BoxFit::kGrows) result.grows = true;
      inside = inside && c[k][d] >= box.sublo[d] && c[k][d] < box.subhi[d];
    }
    if (inside) result.mine.push_back(k);
  }
  return result;
}

}    // namespace PeriSISSM
