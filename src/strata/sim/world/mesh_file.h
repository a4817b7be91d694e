#pragma once
// Triangle meshes from files for `type: mesh` objects: Wavefront OBJ (our small reader) and PLY
// (src/strata/mesh/ply.h).
#include <istream>
#include <string>

#include "strata/mesh/mesh.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {

/// Reads `v x y z` and `f a b c ...` lines (a, a/t, a/t/n, a//n; negative = relative; polygons
/// fan-triangulated); every other line is ignored. InputError "path:line: what" on bad lines, and
/// on files, vertex or triangle counts over the limits of mesh/mesh_file_limits.h.
Mesh readObj(const std::string& path);
/// The same from a stream; `name` (a path) prefixes error messages.
Mesh readObj(std::istream& in, const std::string& name);

/// readObj for .obj, readPly otherwise.
Mesh readMeshFile(const std::string& path);

/// The file's mesh as the shape's single part: turned z-up when shape.y_up, scaled, centred on its
/// footprint, bottom at z = 0. Sets shape.size_m to the result's bounding box size.
/// NOTE: the mesh is used as it is; a mesh with holes (like the Stanford bunny's base) has no
/// well-defined inside, and the signed distance's sign there follows a majority of rays.
Mesh loadShapeMesh(ShapeSpec& shape);

}  // namespace strata::sim
