#pragma once
// Helpers of the session-store tests: scratch folders, poses, raw SQLite access.
#include <Eigen/Geometry>
#include <filesystem>
#include <string>

namespace strata::test {

/// An empty folder under the temp folder, named after `name` and the process id.
std::filesystem::path freshStoreDir(const std::string& name);
/// A pose with a non-trivial rotation and translation, different for each `i`.
Eigen::Isometry3d samplePose(int i);
/// Runs SQL on a database file directly (to forge old, future or foreign files).
void execSql(const std::filesystem::path& db, const std::string& sql);
/// Writes `size` pseudo-random bytes.
void writeRandomFile(const std::filesystem::path& path, std::size_t size, unsigned seed);

}  // namespace strata::test
