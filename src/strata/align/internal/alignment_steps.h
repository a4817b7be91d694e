#pragma once
// Pieces of session_alignment.cpp, separate for size and tests.
#include <Eigen/Geometry>
#include <vector>

#include "strata/align/session_alignment.h"

namespace strata::align::detail {

/// A keyframe loaded for alignment: its depth (kept for the dense verification) and features.
struct LoadedKeyframe {
  std::size_t session = 0;
  std::size_t keyframe = 0;  // index into the session's keyframes
  double timestamp_s = 0.0;
  DepthImage depth;
  CameraIntrinsics intrinsics;
  KeyframeFeatures features;
  KeyframeSurface surface;  // empty when the surface path is off
};

/// InputError naming the first session that breaks alignSessions' contract.
void validateSessions(const std::vector<AlignSession>& sessions);

/// Loads every keyframe's images and extracts (or lifts stored) features, `threads` at a time, in
/// session and keyframe order.
std::vector<LoadedKeyframe> loadKeyframes(const std::vector<AlignSession>& sessions,
                                          const AlignConfig& config,
                                          const AlignProgress& progress);

/// Per frame: the odometry corrected by the keyframes' optimised poses (AlignedSession's rule).
std::vector<Eigen::Isometry3d> correctFrames(const std::vector<double>& frame_timestamps_s,
                                             const std::vector<Eigen::Isometry3d>& frame_T_S_C,
                                             const std::vector<std::size_t>& keyframes,
                                             const std::vector<Eigen::Isometry3d>& keyframe_T_W_C);

/// Clamps the eigenvalues of a loop's information matrix to [1, max_eigenvalue]: dense ICP over
/// thousands of pixels reports sub-millimetre certainty that its model errors (depth noise
/// correlated across pixels, calibration) do not have.
store::Matrix6d clampInformation(const store::Matrix6d& information, double max_eigenvalue);

}  // namespace strata::align::detail
