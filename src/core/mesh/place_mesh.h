/* PERI-SISSM core: a mesh file placed in the simulation box (read_mesh): the vertices'
   positions and areas, and which vertices a sub-domain of the box owns.
*/
#ifndef PERISISSM_MESH_PLACE_MESH_H
#define PERISISSM_MESH_PLACE_MESH_H

#include "mesh/mesh_geometry.h"
#include "mesh/triangle_mesh.h"

#include <array>
#include <vector>

namespace PeriSISSM {

struct PlacedMesh {
  std::vector<std::array<double, 3>> x;    // place() of every vertex, in file order
  std::vector<double> area;                // vertex_areas() of x
  double total_area = 0.0;                 // sum of the triangle areas, in triangle order
};

// Inputs: mesh, placement. Outputs: the placed vertices and their areas.
PlacedMesh place_mesh(const TriangleMesh &mesh, const Placement &placement);

// The box and one sub-domain of it in the coordinates the vertices are checked in (fractional
// coordinates, lo = 0 and hi = 1, for a triclinic box).
struct MeshBox {
  double lo[3], hi[3];          // the box
  double sublo[3], subhi[3];    // the sub-domain, [sublo, subhi) in each direction
  bool periodic[3];
  bool fixed[3][2];    // lower and upper face fixed (LAMMPS's boundary f)
};

struct SubdomainVertices {
  std::vector<int> mine;    // the vertices in the sub-domain, ascending
  bool grows = false;       // some vertex lies beyond a shrink-wrapped face
  int outside = -1;         // the first vertex outside a fixed face (-1: none)
  int dim = 0;              // its direction (0, 1, 2)
  int side = 0;             // its face (0 lower, 1 upper)
};

// fit_to_box of every vertex in every direction, in the order k = 0.., d = 0..2, stopping at the
// first vertex outside a fixed face; a vertex is in the sub-domain when its fitted coordinates
// are.
// Inputs: box, c (the vertices' coordinates in the box, after LAMMPS's remap).
// Outputs: c (fitted), the vertices of the sub-domain or the vertex outside.
SubdomainVertices subdomain_vertices(const MeshBox &box, std::vector<std::array<double, 3>> &c);

}    // namespace PeriSISSM

#endif
