/* PERI-SISSM core: Wavefront OBJ files of triangle meshes (read_mesh).

   Of an OBJ file only the vertices and the faces are read:

     v x y z [w | r g b]       a vertex (extra numbers are ignored)
     f a b c ...               a face: vertex indices a, a/t, a//n or a/t/n; 1 is the first
                               vertex of the file, -1 the last one read so far

   A face of more than three vertices is split into the fan (a b c), (a c d), ... Every other
   line (comments, vt, vn, g, o, s, usemtl, l, ...) is ignored. A malformed v or f line, or an
   index outside the vertices, is an error thrown as std::runtime_error naming the file and the
   line. The mesh is not checked further here (see check_mesh in triangle_mesh.h).
*/
#ifndef PERISISSM_MESH_OBJ_FILE_H
#define PERISISSM_MESH_OBJ_FILE_H

#include "mesh/triangle_mesh.h"

#include <string>

namespace PeriSISSM {

// Inputs: text (the whole file), filename (names it in error messages).
// Outputs: the vertices and triangles with their line numbers.
TriangleMesh parse_obj(const std::string &text, const std::string &filename);

// parse_obj of the file's contents. Throws std::runtime_error ("cannot open mesh file NAME:
// <system error>") when the file cannot be opened.
// Inputs: filename (the path). Outputs: the vertices and triangles with their line numbers.
TriangleMesh read_obj_file(const std::string &filename);

}    // namespace PeriSISSM

#endif
