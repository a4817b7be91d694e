#include "strata/io/odometry_frame_file.h"

#include "strata/core/error.h"
#include "strata/io/tum_format.h"
#include "strata/io/tum_writer.h"

namespace strata {

void writeOdometryFrame(const std::string& path, const Eigen::Isometry3d& T_W_S) {
  writeTumTrajectory(path, {{0.0, T_W_S}},
                     {"the odometry frame S in the world (T_W_S): odometry.txt holds T_S_C",
                      "timestamp (unused) tx ty tz qx qy qz qw (S-to-world)"});
}

Eigen::Isometry3d readOdometryFrame(const std::string& path) {
  const std::vector<tum::TimedPose> poses = tum::readTrajectory(path);
  if (poses.size() != 1) {
    throw InputError(path + ": expected one pose (T_W_S), found " + std::to_string(poses.size()));
  }
  return poses.front().T_W_C;
}

}  // namespace strata
