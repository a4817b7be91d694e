#include "test_utils.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

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

std::filesystem::path freshTempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("strata_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace strata::test
