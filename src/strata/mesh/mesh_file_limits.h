#pragma once
// Limits of the mesh file readers (PLY: mesh/ply.h, OBJ: sim/world/mesh_file.h), checked before the
// data they bound is read or allocated, so a corrupt count cannot make a reader exhaust memory.
#include <cstddef>
#include <cstdint>
#include <string>

#include "strata/core/file_limits.h"

namespace strata {

/// Whole mesh files are read into memory (PLY) or line by line (OBJ); 2 GiB is ~10x the largest
/// scanned meshes worlds use (the Stanford models are a few MB).
inline constexpr FileSizeLimit kMaxMeshFileBytes{"kMaxMeshFileBytes", std::uint64_t{2} << 30};

/// Vertices of one mesh: triangle corners are int, and 2^26 (67 M) vertices is already ~800 MB of
/// positions, far more than any world object needs.
inline constexpr std::size_t kMaxMeshVertices = std::size_t{1} << 26;

/// Triangles of one mesh (after fan triangulation of polygons): 2^27 (134 M), ~1.6 GB of indices.
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 27;

/// Throws InputError "<what> count <count> is over <limit_name> = <limit>" when count > limit.
void checkMeshCount(std::size_t count, std::size_t limit, const char* limit_name, const char* what);

}  // namespace strata
