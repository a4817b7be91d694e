#pragma once
// The object database on disk: a versioned binary file (".objects", docs/objects.md has the
// layout), and the same bytes as one row of the session store when the map lives there.
//
// Format version 2 (version 1 files are read too): magic "STRATAOBJ", u32 version, u32 payload
// bytes, u64 FNV-1a (64 bit) of the payload, then the payload (little endian): f32 map voxel size,
// f32 model voxel size (the config's), u32 session count and i32 sessions, u32 model count, then
// per model: i32 id, i32 merged observations, u32 instance count and per instance (i32 session,
// i32 segment, 12 f64 of T_W_M's top 3x4 rows, f64 match score, f32 observed area, u8 flags:
// bit 0 merged, bit 1 (version 2) the pose is open, ObjectInstance::pose_constrained false),
// u32 TSDF bytes and the model's TSDF as a map file's bytes (map/map_file.h: its config, blocks
// with index and 512 voxels, its own CRC). Meshes and samples are derived and rebuilt on load
// (refreshModel with the loading config; the stored voxel sizes replace the config's).
//
// Errors: InputError naming the file for a missing, truncated, corrupt (checksum) or foreign
// file, and for a newer version ("written by format version 3; this build reads up to 2");
// Error for a failed write. Writes are atomic (temporary file in the same folder, fsync, rename):
// a failure leaves the previous file as it was.
//
// Thread safety: free functions.
#include <string>

#include "strata/objects/object_database.h"

namespace strata::store {
class Store;
}

namespace strata::objects {

inline constexpr unsigned kObjectDatabaseFormatVersion = 2;

std::string serializeObjectDatabase(const ObjectDatabase& database);
/// `name` names the source in errors.
ObjectDatabase deserializeObjectDatabase(const std::string& bytes, const std::string& name,
                                         const DatabaseConfig& config = {});

void saveObjectDatabase(const ObjectDatabase& database, const std::string& path);
ObjectDatabase loadObjectDatabase(const std::string& path, const DatabaseConfig& config = {});

/// The store's copy: one row (table object_database), replaced in one transaction.
void saveObjectDatabase(const ObjectDatabase& database, store::Store& store);
/// nullopt-like: returns false when the store holds none.
bool loadObjectDatabase(store::Store& store, ObjectDatabase& database,
                        const DatabaseConfig& config = {});

}  // namespace strata::objects
