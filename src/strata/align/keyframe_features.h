#pragma once
// Keyframe features for place recognition: ORB corners and 256-bit descriptors (OpenCV) on the
// keyframe's colour image, each with its 3D position in the camera frame from the depth image.
// Frames: C is the keyframe's camera (x right, y down, z forward), metres.
// Thread safety: free functions, no shared state.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/store/store_types.h"

namespace strata::align {

using Descriptor = std::array<std::uint8_t, 32>;  // ORB: 256 bits

struct FeatureConfig {
  int max_features = 1000;      // ORB keypoints kept per keyframe (best response first)
  int pyramid_levels = 8;       // ORB scale pyramid
  float scale_factor = 1.2f;    // ORB pyramid ratio
  float min_depth_m = 0.1f;     // depth outside [min, max] leaves the point unknown (NaN)
  float max_depth_m = 6.0f;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// Keypoints, descriptors and camera-frame points of one keyframe, index-aligned.
struct KeyframeFeatures {
  std::vector<Eigen::Vector2f> keypoints_px;  // pixel centres at integers
  std::vector<Descriptor> descriptors;
  std::vector<Eigen::Vector3f> points_C_m;    // NaN where the depth is missing or out of range
  std::size_t size() const { return keypoints_px.size(); }
};

/// Detects ORB features on the colour image (converted to grey) and lifts them with the depth
/// image (the depth at the rounded keypoint, 0/NaN = unknown). InputError when the images'
/// sizes disagree with the intrinsics or each other. An image without texture gives no features.
KeyframeFeatures extractFeatures(const ColorImage& color, const DepthImage& depth,
                                 const CameraIntrinsics& intrinsics, const FeatureConfig& config);

/// The store's record of the features ("orb", 32-byte descriptors); the points are not stored
/// (they come back from the depth image with liftFeatures).
store::FeatureSet toFeatureSet(const KeyframeFeatures& features);
/// Features from a stored set and the keyframe's depth image. InputError for another format or
/// descriptor size.
KeyframeFeatures liftFeatures(const store::FeatureSet& stored, const DepthImage& depth,
                              const CameraIntrinsics& intrinsics, const FeatureConfig& config);

}  // namespace strata::align
