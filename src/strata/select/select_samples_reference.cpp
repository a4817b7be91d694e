// Host reference of shaders/raycast_samples.comp, and the sample grid both sides share.
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/map/camera_math.h"
#include "strata/select/select_samples.h"
#include "strata/raycast/tsdf_sampling.h"

namespace strata {
namespace {

/// The shader's surface check: the map's TSDF at the measured point on the sample's ray (unit
/// direction dir_W; camera z 1 lies at ray_scale along it), in the shader's order of operations.
SurfaceCheck surfaceCheck(const TsdfMap& map, const Eigen::Vector3f& origin_W,
                          const Eigen::Vector3f& dir_W, float ray_scale, float measured_m,
                          float tolerance_m, float min_weight) {
  const MapConfig& config = map.config();
  // Only depths the map fuses count: beyond its range a surface can never be held.
  if (!(std::isfinite(measured_m) && measured_m > 0.0f && measured_m >= config.min_depth_m &&
        measured_m <= config.max_depth_m)) {
    return SurfaceCheck::kNoMeasurement;
  }
  float tsdf_m = 0.0f;
  const Eigen::Vector3f p_W = origin_W + dir_W * (measured_m * ray_scale);
  const bool held = sampleTsdf(map, p_W, min_weight, &tsdf_m) && std::abs(tsdf_m) <= tolerance_m;
  return held ? SurfaceCheck::kHeld : SurfaceCheck::kNotHeld;
}

}  // namespace

void MeasuredSamples::validate(std::size_t sample_count) const {
  if (depth_m.size() != sample_count) {
    throw InputError("surface check: " + std::to_string(depth_m.size()) + " measured depths for " +
                     std::to_string(sample_count) + " samples");
  }
  if (!(held_tolerance_m >= 0.0f)) throw InputError("surface check: held tolerance must be >= 0");
}

SampleGrid SampleGrid::of(const CameraIntrinsics& intrinsics, int stride_px) {
  intrinsics.validate();
  if (stride_px < 1 || stride_px > std::min(intrinsics.width_px, intrinsics.height_px)) {
    throw InputError("sample stride " + std::to_string(stride_px) +
                     " px: must be in [1, the image's smaller side]");
  }
  SampleGrid grid;
  grid.stride_px = stride_px;
  grid.offset_px = stride_px / 2;
  grid.width = (intrinsics.width_px - grid.offset_px + stride_px - 1) / stride_px;
  grid.height = (intrinsics.height_px - grid.offset_px + stride_px - 1) / stride_px;
  return grid;
}

SampleRaycast raycastSamplesReference(const TsdfMap& map, const CameraIntrinsics& intrinsics,
                                      const Eigen::Isometry3d& T_W_C, int stride_px,
                                      const RaycastOptions& options,
                                      const MeasuredSamples* measured) {
  validatePose(T_W_C, "sample raycast camera");
  SampleRaycast out;
  out.grid = SampleGrid::of(intrinsics, stride_px);
  const std::size_t n = static_cast<std::size_t>(out.grid.count());
  out.hit.assign(n, 0);
  out.depth_m.assign(n, 0.0f);
  out.color_rgba.assign(n, 0);
  out.surface.assign(n, SurfaceCheck::kNoMeasurement);
  if (measured != nullptr) measured->validate(n);
  const MapConfig& config = map.config();
  const FrameCamera camera = FrameCamera::from(intrinsics, T_W_C);
  const Eigen::Matrix3f R_W_C = camera.T_W_C.topLeftCorner<3, 3>();
  const Eigen::Vector3f origin_W = camera.T_W_C.topRightCorner<3, 1>();
  for (int gy = 0; gy < out.grid.height; ++gy) {
    for (int gx = 0; gx < out.grid.width; ++gx) {
      const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(out.grid.pixelU(gx)),
                                             static_cast<float>(out.grid.pixelV(gy)), camera.K);
      const float ray_scale = ray_C.norm();
      const Eigen::Vector3f dir_W = R_W_C * (ray_C / ray_scale);
      const std::size_t i = static_cast<std::size_t>(gy) * out.grid.width + gx;
      if (measured != nullptr) {
        out.surface[i] = surfaceCheck(map, origin_W, dir_W, ray_scale, measured->depth_m[i],
                                      measured->held_tolerance_m, options.min_weight);
      }
      float t_hit = 0.0f;
      if (!raycastRayReference(map, origin_W, dir_W, config.min_depth_m * ray_scale,
                               config.max_depth_m * ray_scale, options, &t_hit)) {
        continue;
      }
      out.hit[i] = 1;
      out.depth_m[i] = t_hit / ray_scale;
      const Eigen::Vector3f p_W = origin_W + dir_W * t_hit;
      const GlobalVoxelIndex nearest = (p_W / config.voxel_size_m).array().floor().cast<int>();
      if (const TsdfVoxel* voxel = observedVoxel(map, nearest, options.min_weight)) {
        out.color_rgba[i] = voxel->color_rgba & 0xFFFFFFu;
      }
    }
  }
  return out;
}

}  // namespace strata
