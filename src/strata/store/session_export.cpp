#include <filesystem>
#include <map>

#include "strata/core/atomic_file.h"
#include "strata/io/tum_format.h"
#include "strata/store/session_import.h"

namespace strata::store {

namespace fs = std::filesystem;

namespace {

std::string poseLine(double timestamp_s, const Eigen::Isometry3d& T) {
  char stamp[32];
  std::snprintf(stamp, sizeof(stamp), "%.6f", timestamp_s);
  return std::string(stamp) + " " + tum::poseToTum(T) + "\n";
}

}  // namespace

std::vector<std::string> exportTrajectories(Store& store, const std::string& out_dir) {
  const std::vector<SessionRecord> sessions = store.sessions();
  std::map<std::string, int> name_uses;
  for (const auto& s : sessions) ++name_uses[s.name];
  std::vector<std::string> written;
  for (const SessionRecord& s : sessions) {
    const std::string name = name_uses[s.name] > 1 ? s.name + "_" + std::to_string(s.id) : s.name;
    const fs::path dir = fs::path(out_dir) / name;
    fs::create_directories(dir);
    std::string odometry = "# session '" + s.name + "' keyframes: odometry T_S_C (camera-to-" +
                           "session), from " + s.source_folder +
                           "\n# timestamp tx ty tz qx qy qz qw\n";
    std::string optimised = "# session '" + s.name +
                            "' keyframes: optimised T_W_C (camera-to-world)\n"
                            "# timestamp tx ty tz qx qy qz qw\n";
    bool any_optimised = false;
    for (const KeyframeRecord& k : store.keyframes(s.id)) {
      odometry += poseLine(k.timestamp_s, k.T_S_C);
      if (k.T_W_C) {
        optimised += poseLine(k.timestamp_s, *k.T_W_C);
        any_optimised = true;
      }
    }
    writeTextAtomically(dir / "odometry.txt", odometry);
    written.push_back((dir / "odometry.txt").string());
    if (any_optimised) {
      writeTextAtomically(dir / "optimised.txt", optimised);
      written.push_back((dir / "optimised.txt").string());
    }
  }
  return written;
}

}  // namespace strata::store
