#pragma once
// PLY mesh files: binary little-endian output readable by MeshLab, Open3D and CloudCompare.
#include <string>

#include "strata/mesh/mesh.h"

namespace strata {

/// Writes vertices (float x y z), normals (float nx ny nz) and colours (uchar red green blue) when
/// the mesh has them, and faces (list uchar int vertex_indices). Atomic: the file is written beside
/// `path` under a temporary name, flushed, then renamed over `path`, so readers never see a partial
/// file. Throws Error naming the path and the system's reason; no temporary file is left behind.
void writePly(const std::string& path, const Mesh& mesh);

/// Reads binary little-endian or ascii PLY with a `vertex` element (x y z, optional nx ny nz and
/// red green blue, any scalar types; other properties are skipped) and an optional `face` element
/// (polygons are fan-triangulated). Throws InputError naming the path on missing, truncated or
/// corrupt files (bad header, indices out of range, unsupported format) and files over the limits of
/// mesh/mesh_file_limits.h (file bytes, vertex and triangle counts).
Mesh readPly(const std::string& path);
/// The same from the file's bytes; `name` (a path) prefixes error messages.
Mesh parsePly(const std::string& data, const std::string& name);

}  // namespace strata
