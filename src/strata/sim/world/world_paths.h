#pragma once
// Where the shipped worlds and the optional shared data live.
#include <string>

namespace strata::sim {

/// $STRATA_WORLDS_DIR when set, else the source tree's worlds/ folder (compile-time).
std::string worldsDir();

/// worldsDir()/room.yaml: the single room that the CLI and demos use by default.
std::string defaultWorldPath();

/// A world given by path ("my/world.yaml") or by shipped name ("office" ->
/// worldsDir()/office.yaml). Returns the path; InputError listing the shipped worlds when neither
/// exists.
std::string findWorld(const std::string& name_or_path);

/// $STRATA_DATA_DIR when set, else ../shared/data beside the source tree; mesh paths written
/// "data:meshes/x.obj" in a world file resolve under it.
std::string sharedDataDir();

/// Resolves a mesh path of a world file: "data:..." under sharedDataDir(), absolute as is, else
/// relative to `base_dir`.
std::string resolveMeshPath(const std::string& path, const std::string& base_dir);

}  // namespace strata::sim
