#include "strata/integrate/normal_estimation.h"

#include <cmath>

namespace strata {
namespace {

Eigen::Vector4f pixelNormal(const DepthImage& depth, const FrameCamera& camera,
                            const MapConfig& config, int u, int v) {
  const Eigen::Vector4f invalid = Eigen::Vector4f::Zero();
  if (u < 1 || v < 1 || u + 1 >= depth.width_px || v + 1 >= depth.height_px) return invalid;
  const float d = depth.at(u, v);
  const float d_left = depth.at(u - 1, v);
  const float d_right = depth.at(u + 1, v);
  const float d_up = depth.at(u, v - 1);
  const float d_down = depth.at(u, v + 1);
  for (float x : {d, d_left, d_right, d_up, d_down}) {
    if (!depthValid(x, config.min_depth_m, config.max_depth_m)) return invalid;
  }
  const float max_jump = config.normal_max_relative_jump * d;
  for (float x : {d_left, d_right, d_up, d_down}) {
    if (std::abs(x - d) > max_jump) return invalid;
  }
  auto point = [&](int pu, int pv, float depth_m) {
    return Eigen::Vector3f(pixelRay(static_cast<float>(pu), static_cast<float>(pv), camera.K) *
                           depth_m);
  };
  const Eigen::Vector3f horizontal = point(u + 1, v, d_right) - point(u - 1, v, d_left);
  const Eigen::Vector3f vertical = point(u, v + 1, d_down) - point(u, v - 1, d_up);
  Eigen::Vector3f n = horizontal.cross(vertical);
  const float length = n.norm();
  if (!(length > 0.0f)) return invalid;
  n /= length;
  if (n.dot(pixelRay(static_cast<float>(u), static_cast<float>(v), camera.K)) > 0.0f) n = -n;
  return Eigen::Vector4f(n.x(), n.y(), n.z(), 1.0f);
}

}  // namespace

std::vector<Eigen::Vector4f> estimateNormalsReference(const DepthImage& depth,
                                                      const FrameCamera& camera,
                                                      const MapConfig& config) {
  std::vector<Eigen::Vector4f> normals(depth.depth_m.size(), Eigen::Vector4f::Zero());
  for (int v = 0; v < depth.height_px; ++v) {
    for (int u = 0; u < depth.width_px; ++u) {
      normals[static_cast<std::size_t>(v) * depth.width_px + u] =
          pixelNormal(depth, camera, config, u, v);
    }
  }
  return normals;
}

}  // namespace strata
