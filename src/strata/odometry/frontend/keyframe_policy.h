#pragma once
// Keyframe policy of the front end. A frame is a keyframe when any of these holds:
//   1. it is the first frame, or tracking was lost (the back end restarts from it);
//   2. the mean parallax of the features it shares with the last keyframe reaches
//      min_parallax_px (rotation-compensated when every frame since carried a rotation
//      prediction, so turning on the spot does not count as parallax);
//   3. fewer than min_tracked_fraction of the last keyframe's features are still tracked;
//   4. max_interval_s passed since the last keyframe (bounds IMU preintegration spans).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "strata/odometry/frontend/feature_observation.h"

namespace strata::odometry {

struct KeyframeConfig {
  double min_parallax_px = 10.0;      // lower: more keyframes, weaker triangulation each
  double min_tracked_fraction = 0.6;  // of the last keyframe's features
  double max_interval_s = 0.5;        // longest gap between keyframes

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// Not thread safe (one instance per tracker).
class KeyframePolicy {
 public:
  explicit KeyframePolicy(KeyframeConfig config);

  /// Decides for the current frame; a keyframe becomes the new reference. `R_cur_prev` as the
  /// tracker's prediction (may be absent). Writes the measured parallax to *parallax_px.
  bool decide(std::int64_t timestamp_ns, const std::vector<FeatureObservation>& features,
              const std::optional<Eigen::Matrix3d>& R_cur_prev, double focal_px, bool lost,
              double* parallax_px);

 private:
  KeyframeConfig config_;
  bool has_keyframe_ = false;
  std::int64_t keyframe_time_ns_ = 0;
  std::unordered_map<std::uint64_t, Eigen::Vector2d> reference_xy_;  // id -> xy at keyframe
  std::optional<Eigen::Matrix3d> R_cur_keyframe_;  // absent once a frame lacked a prediction
};

}  // namespace strata::odometry
