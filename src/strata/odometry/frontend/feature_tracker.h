#pragma once
// The visual front end: per frame, track the previous frame's features with pyramidal KLT
// (initialised from a gyro-predicted rotation when given), drop those failing the
// forward-backward check, reject geometric outliers (geometric_check.h), detect new corners where
// tracks are sparse (corner_detector.h), match every feature into the right image
// (stereo_matcher.h), and decide keyframes (keyframe_policy.h). See docs/odometry.md "Front end".
#include <chrono>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "strata/odometry/frontend/appearance_check.h"
#include "strata/odometry/frontend/camera.h"
#include "strata/odometry/frontend/corner_detector.h"
#include "strata/odometry/frontend/feature_observation.h"
#include "strata/odometry/frontend/geometric_check.h"
#include "strata/odometry/frontend/keyframe_policy.h"
#include "strata/odometry/frontend/klt.h"
#include "strata/odometry/frontend/stereo_matcher.h"

namespace strata::odometry {

struct FrontendConfig {
  DetectorConfig detector;
  KltConfig klt;
  GeometricCheckConfig geometry;
  StereoMatchConfig stereo;
  KeyframeConfig keyframe;
  /// Fewer surviving tracks than this (after the first frame) sets FrontendStats::lost.
  int min_tracked = 20;
  /// Tracks may not end closer than this to the image edge (KLT window support).
  double border_px = 4.0;
  /// Appearance check (appearance_check.h): a track whose patch correlates below
  /// min_appearance_ncc with its patch at detection is dropped; 0 turns the check off. Lower
  /// keeps more sliding T-junctions, higher drops more true points under strong perspective.
  int appearance_patch_px = 15;
  double min_appearance_ncc = 0.7;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// Not thread safe: one tracker per camera rig, frames in time order. OpenCV's KLT runs on
/// cv::getNumThreads() threads; the caller sets cv::setNumThreads (time per frame with one
/// thread: docs/odometry.md, "Speed").
class FeatureTracker {
 public:
  /// Mono: only the left camera is used. Throws InputError for a bad camera or config.
  FeatureTracker(const Camera& camera, FrontendConfig config);
  /// Stereo: every feature is also matched into the right camera.
  FeatureTracker(const StereoCamera& camera, FrontendConfig config);

  /// Processes one frame. `left` (and `right` for a stereo tracker; ignored for mono) must be
  /// non-empty single-channel 8-bit images of the calibrated size, else InputError naming the
  /// eye and the problem. `R_Ck_Ckm1` (optional): the left camera's rotation between the frames,
  /// p_Ck = R_Ck_Ckm1 p_Ckm1 for a direction (cameraRotation() makes it from the IMU's R_Bk_Bkm1);
  /// it initialises KLT at the infinite-depth prediction and compensates parallax.
  /// Timestamps must increase (InputError otherwise).
  FrameFeatures process(std::int64_t timestamp_ns, const cv::Mat& left, const cv::Mat& right,
                        const std::optional<Eigen::Matrix3d>& R_Ck_Ckm1 = std::nullopt);
  /// Mono form.
  FrameFeatures process(std::int64_t timestamp_ns, const cv::Mat& left,
                        const std::optional<Eigen::Matrix3d>& R_Ck_Ckm1 = std::nullopt) {
    return process(timestamp_ns, left, cv::Mat(), R_Ck_Ckm1);
  }

  const FrontendConfig& config() const { return config_; }
  bool isStereo() const { return stereo_; }

 private:
  struct Track {
    std::uint64_t id;
    cv::Point2f uv_px;
    Eigen::Vector2d xy_norm;
    int length;
    std::optional<Eigen::Vector2d> uv_right_px;  // last right-eye position, stereo guess
    cv::Mat patch;  // normalizedPatch at detection (appearance_check.h); empty = flat
  };

  void checkImage(const cv::Mat& image, const Camera& camera) const;
  void trackPrevious(const std::vector<cv::Mat>& pyramid,
                     const std::optional<Eigen::Matrix3d>& R_Ck_Ckm1, FrontendStats* stats);
  void addNewCorners(const cv::Mat& left, FrontendStats* stats);
  void matchRight(const std::vector<cv::Mat>& pyramid_left, const cv::Mat& right,
                  std::vector<std::optional<StereoMatch>>* matches, FrontendStats* stats);

  StereoCamera camera_;
  bool stereo_;
  FrontendConfig config_;
  KeyframePolicy keyframes_;
  std::vector<Track> tracks_;
  std::vector<cv::Mat> previous_pyramid_;
  std::optional<std::int64_t> previous_timestamp_ns_;
  std::uint64_t next_id_ = 0;
};

}  // namespace strata::odometry
