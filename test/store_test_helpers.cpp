#include "store_test_helpers.h"

#include <unistd.h>

#include <fstream>
#include <random>

#include "strata/store/sqlite_db.h"

namespace strata::test {

namespace fs = std::filesystem;

fs::path freshStoreDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("strata_test_store_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Eigen::Isometry3d samplePose(int i) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.3 + 0.1 * i, Eigen::Vector3d(1, 2, 3 + i).normalized())
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.5 * i, -0.25 * i + 1.0, 1.5 + 0.01 * i);
  return T;
}

void execSql(const fs::path& db, const std::string& sql) {
  store::Database database(db.string(), true);
  database.exec(sql, "test SQL");
}

void writeRandomFile(const fs::path& path, std::size_t size, unsigned seed) {
  std::mt19937 rng(seed);
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace strata::test
