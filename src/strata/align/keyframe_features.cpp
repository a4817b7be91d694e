#include "strata/align/keyframe_features.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "strata/core/error.h"

namespace strata::align {
namespace {

constexpr const char* kFormat = "orb";

std::string sizeText(int width_px, int height_px) {
  return std::to_string(width_px) + "x" + std::to_string(height_px);
}

void checkDepth(const DepthImage& depth, const CameraIntrinsics& intrinsics) {
  intrinsics.validate();
  if (depth.width_px != intrinsics.width_px || depth.height_px != intrinsics.height_px ||
      depth.depth_m.size() != static_cast<std::size_t>(depth.width_px) * depth.height_px) {
    throw InputError("keyframe features: depth image " + sizeText(depth.width_px, depth.height_px) +
                     " does not match the intrinsics' " +
                     sizeText(intrinsics.width_px, intrinsics.height_px));
  }
}

void checkColor(const ColorImage& color, const CameraIntrinsics& intrinsics) {
  if (color.width_px != intrinsics.width_px || color.height_px != intrinsics.height_px ||
      color.rgb.size() != static_cast<std::size_t>(color.width_px) * color.height_px * 3) {
    throw InputError("keyframe features: colour image " +
                     sizeText(color.width_px, color.height_px) +
                     " does not match the intrinsics' and depth image's " +
                     sizeText(intrinsics.width_px, intrinsics.height_px));
  }
}

cv::Mat greyOf(const ColorImage& color) {
  // NOTE: cv::Mat over the caller's bytes, no copy; cvtColor writes a new image.
  const cv::Mat rgb(color.height_px, color.width_px, CV_8UC3,
                    const_cast<std::uint8_t*>(color.rgb.data()));
  cv::Mat grey;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  return grey;
}

// The camera-frame point of pixel (u, v) with the depth at the rounded pixel; NaN when unknown.
Eigen::Vector3f liftPoint(const Eigen::Vector2f& uv_px, const DepthImage& depth,
                          const CameraIntrinsics& intrinsics, const FeatureConfig& config) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  const int u = static_cast<int>(std::lround(uv_px.x()));
  const int v = static_cast<int>(std::lround(uv_px.y()));
  if (u < 0 || v < 0 || u >= depth.width_px || v >= depth.height_px) {
    return Eigen::Vector3f::Constant(kNaN);
  }
  const float z_m = depth.at(u, v);
  if (!(z_m >= config.min_depth_m && z_m <= config.max_depth_m)) {
    return Eigen::Vector3f::Constant(kNaN);
  }
  return {(uv_px.x() - intrinsics.cx_px) / intrinsics.fx_px * z_m,
          (uv_px.y() - intrinsics.cy_px) / intrinsics.fy_px * z_m, z_m};
}

void liftAll(KeyframeFeatures& features, const DepthImage& depth,
             const CameraIntrinsics& intrinsics, const FeatureConfig& config) {
  features.points_C_m.clear();
  features.points_C_m.reserve(features.size());
  for (const Eigen::Vector2f& uv_px : features.keypoints_px) {
    features.points_C_m.push_back(liftPoint(uv_px, depth, intrinsics, config));
  }
}

}  // namespace

void FeatureConfig::validate() const {
  if (max_features < 1) throw InputError("FeatureConfig: max_features must be >= 1");
  if (pyramid_levels < 1) throw InputError("FeatureConfig: pyramid_levels must be >= 1");
  if (!(scale_factor > 1.0f && scale_factor < 4.0f)) {
    throw InputError("FeatureConfig: scale_factor must be in (1, 4)");
  }
  if (!(min_depth_m >= 0.0f)) throw InputError("FeatureConfig: min_depth_m must be >= 0");
  if (!(max_depth_m > min_depth_m)) {
    throw InputError("FeatureConfig: max_depth_m must be greater than min_depth_m");
  }
}

KeyframeFeatures extractFeatures(const ColorImage& color, const DepthImage& depth,
                                 const CameraIntrinsics& intrinsics, const FeatureConfig& config) {
  config.validate();
  checkDepth(depth, intrinsics);
  checkColor(color, intrinsics);

  const cv::Ptr<cv::ORB> orb =
      cv::ORB::create(config.max_features, config.scale_factor, config.pyramid_levels);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(greyOf(color), cv::noArray(), keypoints, descriptors);

  KeyframeFeatures features;
  if (keypoints.empty() || descriptors.empty()) return features;
  features.keypoints_px.reserve(keypoints.size());
  features.descriptors.resize(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    features.keypoints_px.emplace_back(keypoints[i].pt.x, keypoints[i].pt.y);
    std::memcpy(features.descriptors[i].data(), descriptors.ptr<std::uint8_t>(static_cast<int>(i)),
                sizeof(Descriptor));
  }
  liftAll(features, depth, intrinsics, config);
  return features;
}

store::FeatureSet toFeatureSet(const KeyframeFeatures& features) {
  if (features.descriptors.size() != features.size()) {
    throw InputError("toFeatureSet: " + std::to_string(features.size()) + " keypoints but " +
                     std::to_string(features.descriptors.size()) + " descriptors");
  }
  store::FeatureSet stored;
  stored.format = kFormat;
  stored.descriptor_bytes = sizeof(Descriptor);
  stored.keypoints_px = features.keypoints_px;
  stored.descriptors.resize(features.size() * sizeof(Descriptor));
  for (std::size_t i = 0; i < features.size(); ++i) {
    std::memcpy(stored.descriptors.data() + i * sizeof(Descriptor), features.descriptors[i].data(),
                sizeof(Descriptor));
  }
  return stored;
}

KeyframeFeatures liftFeatures(const store::FeatureSet& stored, const DepthImage& depth,
                              const CameraIntrinsics& intrinsics, const FeatureConfig& config) {
  config.validate();
  checkDepth(depth, intrinsics);
  if (stored.format != kFormat || stored.descriptor_bytes != sizeof(Descriptor)) {
    throw InputError("liftFeatures: stored features are '" + stored.format + "' with " +
                     std::to_string(stored.descriptor_bytes) + "-byte descriptors, not '" +
                     kFormat + "' with " + std::to_string(sizeof(Descriptor)));
  }
  const std::size_t count = stored.keypoints_px.size();
  if (stored.descriptors.size() != count * sizeof(Descriptor)) {
    throw InputError("liftFeatures: " + std::to_string(count) + " keypoints but " +
                     std::to_string(stored.descriptors.size()) + " descriptor bytes");
  }
  KeyframeFeatures features;
  features.keypoints_px = stored.keypoints_px;
  features.descriptors.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    std::memcpy(features.descriptors[i].data(), stored.descriptors.data() + i * sizeof(Descriptor),
                sizeof(Descriptor));
  }
  liftAll(features, depth, intrinsics, config);
  return features;
}

}  // namespace strata::align
