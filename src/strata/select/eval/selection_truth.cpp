#include "strata/select/eval/selection_truth.h"

#include <algorithm>
#include <cmath>

#include "strata/core/error.h"
#include "strata/map/camera_math.h"
#include "strata/raycast/tsdf_sampling.h"

namespace strata::selection {
namespace {

/// One looked-at pixel with a valid measurement.
struct TruthPixel {
  std::size_t index;      // in the image
  Eigen::Vector3f ray_C;  // z = 1
  float true_depth_m;
};

std::vector<TruthPixel> validPixels(const sim::SimulatedFrame& frame, const CameraIntrinsics& k,
                                    int stride) {
  std::vector<TruthPixel> out;
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  for (int v = stride / 2; v < k.height_px; v += stride) {
    for (int u = stride / 2; u < k.width_px; u += stride) {
      const std::size_t i = static_cast<std::size_t>(v) * k.width_px + u;
      const float measured = frame.depth.depth_m[i];
      const float truth = frame.depth_true.depth_m[i];
      if (!(measured > 0.0f) || !(truth > 0.0f)) continue;
      out.push_back({i, pixelRay(static_cast<float>(u), static_cast<float>(v), K), truth});
    }
  }
  return out;
}

bool observedAt(const TsdfMap& map, const Eigen::Vector3f& p_W, float min_weight) {
  const GlobalVoxelIndex v = (p_W / map.config().voxel_size_m).array().floor().cast<int>();
  return observedVoxel(map, v, min_weight) != nullptr;
}

/// Does the map hold the true surface at p_W: is its interpolated distance there within
/// `tolerance_m` of zero? A voxel seen only as free space (before an object arrived, or carved by
/// grazing rays past a thin chair back) is observed but does not hold the surface.
bool holdsSurfaceAt(const TsdfMap& map, const Eigen::Vector3f& p_W, float min_weight,
                    float tolerance_m) {
  float tsdf_m = 0.0f;
  return sampleTsdf(map, p_W, min_weight, &tsdf_m) && std::abs(tsdf_m) <= tolerance_m;
}

Eigen::Vector3f surfacePoint(const TruthPixel& p, const Eigen::Isometry3f& T_W_C) {
  return T_W_C * Eigen::Vector3f(p.ray_C * p.true_depth_m);
}

/// Per pixel: does the surface the map last observed along its ray sit elsewhere?
std::vector<std::uint8_t> surfaceMoved(const std::vector<TruthPixel>& pixels,
                                       const Eigen::Isometry3f& T_W_C, const MapHistory& history,
                                       float tolerance_m) {
  std::vector<sim::Ray> rays(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    rays[i].origin_W = T_W_C.translation();
    rays[i].direction_W = T_W_C.linear() * pixels[i].ray_C.normalized();
  }
  const std::vector<float> observed_m = history.lastObservedDistance(rays);
  std::vector<std::uint8_t> moved(pixels.size(), 0);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const float true_t = pixels[i].true_depth_m * pixels[i].ray_C.norm();
    moved[i] = observed_m[i] >= 0.0f && std::abs(observed_m[i] - true_t) > tolerance_m;
  }
  return moved;
}

}  // namespace

void TruthConfig::validate() const {
  if (!(min_positive_fraction > 0.0 && min_positive_fraction < 1.0)) {
    throw InputError("min_positive_fraction must be in (0, 1)");
  }
  if (!(surface_tolerance_m > 0.0f)) throw InputError("surface_tolerance_m must be > 0");
  if (pixel_stride < 1) throw InputError("pixel_stride must be >= 1");
  if (!(min_weight > 0.0f)) throw InputError("min_weight must be > 0");
  if (!(held_tolerance_voxels > 0.0f)) throw InputError("held_tolerance_voxels must be > 0");
}

KeyframeTruth keyframeTruth(const sim::SimulatedFrame& frame, const Eigen::Isometry3d& true_T_W_C,
                            const CameraIntrinsics& intrinsics, const std::vector<int>& changed_ids,
                            const MapHistory& history, const TsdfMap& map,
                            const TruthConfig& config) {
  config.validate();
  const Eigen::Isometry3f T_W_C = true_T_W_C.cast<float>();
  const std::vector<TruthPixel> pixels = validPixels(frame, intrinsics, config.pixel_stride);
  const std::vector<std::uint8_t> moved =
      surfaceMoved(pixels, T_W_C, history, config.surface_tolerance_m);
  const float held_tolerance_m = config.held_tolerance_voxels * map.config().voxel_size_m;
  KeyframeTruth t;
  t.valid_pixels = static_cast<int>(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const int id = frame.object_ids.ids[pixels[i].index];
    const bool changed = moved[i] || std::binary_search(changed_ids.begin(), changed_ids.end(), id);
    const bool unmapped = !holdsSurfaceAt(map, surfacePoint(pixels[i], T_W_C), config.min_weight,
                                          held_tolerance_m);
    t.changed_pixels += changed;
    t.unmapped_pixels += unmapped;
    t.positive_pixels += changed || unmapped;
  }
  t.positive_fraction =
      t.valid_pixels > 0 ? static_cast<double>(t.positive_pixels) / t.valid_pixels : 0.0;
  t.positive = t.positive_fraction >= config.min_positive_fraction;
  return t;
}

void addSurfaceCoverage(const sim::SimulatedFrame& frame, const Eigen::Isometry3d& true_T_W_C,
                        const CameraIntrinsics& intrinsics, const TsdfMap& map,
                        const TruthConfig& config, SurfaceCoverage& coverage) {
  const Eigen::Isometry3f T_W_C = true_T_W_C.cast<float>();
  for (const TruthPixel& p : validPixels(frame, intrinsics, config.pixel_stride)) {
    ++coverage.points;
    coverage.observed += observedAt(map, surfacePoint(p, T_W_C), config.min_weight);
  }
}

}  // namespace strata::selection
