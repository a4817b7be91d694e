#include "test_utils.h"

#include <cstdlib>
#include <filesystem>

namespace strata::test {

std::string sharedDataDir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("STRATA_DATA_DIR"); env != nullptr && fs::is_directory(env)) {
    return env;
  }
  const fs::path built_in = STRATA_SHARED_DATA_DIR;
  return fs::is_directory(built_in) ? built_in.lexically_normal().string() : std::string();
}

std::string sharedDataPath(const std::string& relative) {
  const std::string root = sharedDataDir();
  if (root.empty()) return {};
  const std::filesystem::path path = std::filesystem::path(root) / relative;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

}  // namespace strata::test
