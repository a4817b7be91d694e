#include "strata/change/eval/evaluation_visibility.h"

#include <cmath>

#include "strata/core/error.h"

namespace strata::change {
namespace {

std::uint64_t cubeKey(const Eigen::Vector3f& p, float spacing_m) {
  constexpr std::int64_t kBias = 1 << 20;
  const Eigen::Vector3i c = (p / spacing_m).array().floor().cast<int>();
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    key |= (static_cast<std::uint64_t>(c[k] + kBias) & 0x1FFFFF) << (21 * k);
  }
  return key;
}

/// The fusion updates a voxel from the pixel its centre projects to: the cube counts as seen in
/// this frame when that pixel has a measured depth and its true surface lies within the cube's
/// reach (not occluded, not far behind).
bool centreSeen(const sim::SimulatedFrame& frame, const CameraIntrinsics& k,
                const Eigen::Isometry3f& T_C_W, const Eigen::Vector3f& centre_W, float spacing_m) {
  const Eigen::Vector3f c = T_C_W * centre_W;
  if (!(c.z() > 0.0f)) return false;
  const int u = static_cast<int>(std::floor(k.fx_px * c.x() / c.z() + k.cx_px + 0.5f));
  const int v = static_cast<int>(std::floor(k.fy_px * c.y() / c.z() + k.cy_px + 0.5f));
  if (u < 0 || v < 0 || u >= frame.depth.width_px || v >= frame.depth.height_px) return false;
  return frame.depth.at(u, v) > 0.0f &&
         std::abs(frame.depth_true.at(u, v) - c.z()) <= 2.0f * spacing_m;
}

}  // namespace

VisibleSurface::VisibleSurface(float spacing_m, int pixel_stride)
    : spacing_m_(spacing_m), pixel_stride_(pixel_stride) {
  if (!std::isfinite(spacing_m) || spacing_m <= 0.0f || pixel_stride < 1) {
    throw InputError("VisibleSurface: spacing_m must be positive and pixel_stride >= 1");
  }
}

void VisibleSurface::addView(int object_id, const Eigen::Vector3f& p_W, int views,
                             std::uint64_t frame) {
  Cloud& cloud = clouds_[object_id];
  const auto [it, added] = cloud.cubes.emplace(cubeKey(p_W, spacing_m_), cloud.points.size());
  if (added) {
    cloud.points.push_back(p_W);
    cloud.views.push_back(views);
    cloud.last_frame.push_back(frame);
  } else if (cloud.last_frame[it->second] != frame) {
    cloud.views[it->second] += views;
    cloud.last_frame[it->second] = frame;
  }
}

void VisibleSurface::addPoint(int object_id, const Eigen::Vector3f& p_W, int views) {
  addView(object_id, p_W, views, ++frames_);  // a view of its own
}

void VisibleSurface::addFrame(const sim::SimulatedFrame& frame, const CameraIntrinsics& k,
                              const Eigen::Isometry3d& T_W_C) {
  const Eigen::Isometry3f T = T_W_C.cast<float>();
  const Eigen::Isometry3f T_C_W = T.inverse();
  const std::uint64_t frame_number = ++frames_;
  for (int v = 0; v < frame.depth.height_px; v += pixel_stride_) {
    for (int u = 0; u < frame.depth.width_px; u += pixel_stride_) {
      const float measured = frame.depth.at(u, v), z = frame.depth_true.at(u, v);
      const int id = frame.object_ids.at(u, v);
      if (!(measured > 0.0f) || !(z > 0.0f) || id < 0) continue;
      const Eigen::Vector3f p_C((static_cast<float>(u) - k.cx_px) / k.fx_px * z,
                                (static_cast<float>(v) - k.cy_px) / k.fy_px * z, z);
      const Eigen::Vector3f p_W = T * p_C;
      const Eigen::Vector3f centre_W =
          ((p_W / spacing_m_).array().floor() + 0.5f).matrix() * spacing_m_;
      addView(id, p_W, centreSeen(frame, k, T_C_W, centre_W, spacing_m_) ? 1 : 0, frame_number);
    }
  }
}

std::vector<Eigen::Vector3f> VisibleSurface::points(int object_id, int min_views) const {
  std::vector<Eigen::Vector3f> out;
  const auto it = clouds_.find(object_id);
  if (it == clouds_.end()) return out;
  for (std::size_t i = 0; i < it->second.points.size(); ++i) {
    if (it->second.views[i] >= min_views) out.push_back(it->second.points[i]);
  }
  return out;
}

std::vector<int> VisibleSurface::objectIds() const {
  std::vector<int> ids;
  for (const auto& [id, cloud] : clouds_) ids.push_back(id);
  return ids;
}

}  // namespace strata::change
