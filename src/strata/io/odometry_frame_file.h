#pragma once
// odometry_frame.txt: where a session's odometry frame S lies in the world, T_W_S, beside the
// session's odometry.txt (T_S_C) in a TUM folder, so an evaluation can check a recovered T_W_S.
// One TUM trajectory line, `0 tx ty tz qx qy qz qw` (S-to-world; the timestamp is unused).
#include <Eigen/Geometry>
#include <string>

namespace strata {

/// Writes T_W_S to `path` atomically. Error when it cannot be written.
void writeOdometryFrame(const std::string& path, const Eigen::Isometry3d& T_W_S);

/// Reads T_W_S back. Throws InputError naming the file when it is missing, malformed or does not
/// hold exactly one pose.
Eigen::Isometry3d readOdometryFrame(const std::string& path);

}  // namespace strata
