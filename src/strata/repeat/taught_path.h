#pragma once
// A taught path as the repeat reads it from a teach folder (teach_recording.h): the camera
// poses of taught_path.txt in the map frame (the teach's odometry: what the robot believes it
// flew) and, for scoring only, the true positions of the same frames (groundtruth.txt).
// Frames: map M (= the teach's odometry frame), world W (the simulator's truth). Metres, radians.
// Errors: InputError naming the file for a missing or malformed file, or one with fewer than two
// poses; truth that does not match the taught frames is refused.
// Thread safety: a value.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace strata::repeat {

struct TaughtPath {
  std::vector<double> timestamp_s;
  std::vector<Eigen::Vector3f> p_M;  // taught camera centres, map frame
  std::vector<float> yaw_rad;        // their headings about +z (map frame)
  std::vector<Eigen::Vector3f> p_W;  // the same frames' true centres (scoring only)
  std::vector<double> s_m;           // arc length along p_M from the first pose

  double length_m() const { return s_m.empty() ? 0.0 : s_m.back(); }
  /// The point at arc length s (clamped to the path).
  Eigen::Vector3f at(double s_m) const;
  /// Points of the path between arc lengths s0 and s1 (both ends interpolated), s0 <= s1.
  std::vector<Eigen::Vector3f> between(double s0_m, double s1_m) const;

  /// Reads dir/taught_path.txt and dir/groundtruth.txt.
  static TaughtPath load(const std::string& dir);
};

/// Distance from p to the polyline (metres); infinity for an empty one.
float distanceToPolyline(const Eigen::Vector3f& p, const std::vector<Eigen::Vector3f>& polyline);

/// The polyline simplified (Douglas-Peucker: every removed point within tolerance_m of the
/// simplified one); the ends are kept.
std::vector<Eigen::Vector3f> simplifyPolyline(const std::vector<Eigen::Vector3f>& points,
                                              float tolerance_m);

}  // namespace strata::repeat
