#pragma once
// What the visual front end hands the back end, one FrameFeatures per stereo (or mono) frame.
// Every observation is in the left camera (camera 0) with, where stereo matching succeeded, the
// same point in the right camera. Pixel coordinates are raw (distorted) image coordinates;
// normalized coordinates are undistorted (x / z, y / z in that camera's frame), which is what a
// back end's reprojection residual wants.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace strata::odometry {

struct FeatureObservation {
  /// Persistent over the track's life; never reused (a lost and re-detected point gets a new id).
  std::uint64_t track_id = 0;
  Eigen::Vector2d uv_left_px = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> uv_right_px;
  Eigen::Vector2d xy_left_norm = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> xy_right_norm;
  /// Frames this track has been seen in, this one included (1 = detected in this frame).
  int track_length = 1;
};

/// Why features were dropped or added, per frame; the front end's failures show up here.
struct FrontendStats {
  int detected = 0;             // new corners added this frame
  int tracked = 0;              // previous tracks that survived every check into this frame
  int rejected_klt = 0;         // KLT did not converge or left the image
  int rejected_fwd_bwd = 0;     // backward KLT did not return within fwd_bwd_max_px
  int rejected_appearance = 0;  // patch no longer like the one detected (appearance_check.h)
  int rejected_geometry = 0;    // outliers of the RANSAC essential matrix / homography
  int stereo_matched = 0;       // features with a right-camera observation
  int stereo_rejected = 0;      // right-eye KLT failed, fwd-bwd, epipolar or depth bounds
  /// Median frame-to-frame displacement of the tracked features, pixels (0 on the first frame).
  double median_flow_px = 0.0;
  /// Mean parallax of the features shared with the last keyframe, pixels (rotation-compensated
  /// where predictions were given).
  double parallax_px = 0.0;
  /// True when fewer than Config::min_tracked tracks survived from the previous frame (and it
  /// was not the first frame): the back end should not trust the frame-to-frame link.
  bool lost = false;
  /// Geometric model of the outlier check: 'E' essential matrix, 'H' homography (small
  /// parallax), '-' none (first frame or too few tracks).
  char geometric_model = '-';
  double process_time_ms = 0.0;  // wall time of FeatureTracker::process, and its stages:
  double pyramid_ms = 0.0;       //   left image pyramid
  double track_ms = 0.0;         //   KLT forward-backward, appearance and geometric checks
  double detect_ms = 0.0;        //   new corners
  double stereo_ms = 0.0;        //   right pyramid and stereo matching
};

struct FrameFeatures {
  std::int64_t timestamp_ns = 0;
  std::vector<FeatureObservation> features;
  bool is_keyframe = false;
  FrontendStats stats;
};

}  // namespace strata::odometry
