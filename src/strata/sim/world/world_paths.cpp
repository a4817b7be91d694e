#include "strata/sim/world/world_paths.h"

#include <cstdlib>
#include <filesystem>

#include "strata/core/error.h"

#ifndef STRATA_SOURCE_DIR
#error "STRATA_SOURCE_DIR must be defined by the build (src/strata/sim/CMakeLists.txt)"
#endif

namespace strata::sim {
namespace {

std::string envOr(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return (value != nullptr && *value != '\0') ? std::string(value) : fallback;
}

}  // namespace

std::string worldsDir() { return envOr("STRATA_WORLDS_DIR", STRATA_SOURCE_DIR "/worlds"); }

std::string defaultWorldPath() { return worldsDir() + "/room.yaml"; }

std::string findWorld(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  if (fs::is_regular_file(name_or_path)) return name_or_path;
  const std::string shipped = worldsDir() + "/" + name_or_path + ".yaml";
  if (fs::is_regular_file(shipped)) return shipped;
  std::string names;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(worldsDir(), ignored)) {
    if (entry.path().extension() == ".yaml") names += " " + entry.path().stem().string();
  }
  throw InputError("world '" + name_or_path + "' not found: no such file, and no " + shipped +
                   " (shipped worlds:" + (names.empty() ? " none found" : names) +
                   "; set STRATA_WORLDS_DIR to their folder)");
}

std::string sharedDataDir() {
  return envOr("STRATA_DATA_DIR", STRATA_SOURCE_DIR "/../shared/data");
}

std::string resolveMeshPath(const std::string& path, const std::string& base_dir) {
  const std::string data_prefix = "data:";
  if (path.rfind(data_prefix, 0) == 0) return sharedDataDir() + "/" + path.substr(5);
  if (std::filesystem::path(path).is_absolute() || base_dir.empty()) return path;
  return (std::filesystem::path(base_dir) / path).string();
}

}  // namespace strata::sim
