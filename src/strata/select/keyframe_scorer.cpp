// Keyframe scoring on the device (raycast_samples.comp) and its host reference.
#include "strata/select/keyframe_scorer.h"

#include "strata/map/device_tsdf_map.h"

namespace strata::selection {
namespace {

RaycastOptions raycastOptions(const ScorerConfig& config) {
  RaycastOptions options;
  options.min_weight = config.min_weight;
  options.tsdf_layer = config.tsdf_layer;
  return options;
}

}  // namespace

MeasuredSamples measuredSamples(const SampleGrid& grid, const RgbdFrame& frame,
                                const ScorerConfig& config, float voxel_size_m) {
  MeasuredSamples measured;
  std::vector<std::uint32_t> color_rgb;
  keyframeAtSamples(grid, frame, measured.depth_m, color_rgb);
  measured.held_tolerance_m = config.held_tolerance_voxels * voxel_size_m;
  return measured;
}

KeyframeScore scoreKeyframeReference(const TsdfMap& map, const RgbdFrame& frame,
                                     const CameraIntrinsics& intrinsics, const ScorerConfig& config,
                                     SampleRaycast* rendered) {
  config.validate();
  validateFrame(frame, intrinsics);
  const MeasuredSamples measured =
      measuredSamples(SampleGrid::of(intrinsics, config.sample_stride_px), frame, config,
                      map.config().voxel_size_m);
  SampleRaycast samples = raycastSamplesReference(
      map, intrinsics, frame.T_W_C, config.sample_stride_px, raycastOptions(config), &measured);
  KeyframeScore score = scoreSamples(samples, frame, config);
  if (rendered != nullptr) *rendered = std::move(samples);
  return score;
}

KeyframeScorer::KeyframeScorer(vk::Context& context, const ScorerConfig& config)
    : config_(config), kernel_(context), difference_kernel_(context) {
  config_.validate();
}

KeyframeScore KeyframeScorer::score(DeviceTsdfMap& map, const RgbdFrame& frame,
                                    const CameraIntrinsics& intrinsics, double* device_ms,
                                    SampleRaycast* rendered, SampleDifferences* differences) {
  validateFrame(frame, intrinsics);
  double raycast_ms = 0.0, difference_ms = 0.0;
  // The keyframe at the grid's pixels, once: the raycast's surface check reads its depth, the
  // differences kernel its depth and colour.
  const SampleGrid grid = SampleGrid::of(intrinsics, config_.sample_stride_px);
  MeasuredSamples measured;
  std::vector<std::uint32_t> color_rgb;
  keyframeAtSamples(grid, frame, measured.depth_m, color_rgb);
  measured.held_tolerance_m = config_.held_tolerance_voxels * map.config().voxel_size_m;
  SampleRaycast samples = kernel_.run(map, intrinsics, frame.T_W_C, config_.sample_stride_px,
                                      raycastOptions(config_), &raycast_ms, &measured);
  SampleDifferences per_sample =
      difference_kernel_.run(kernel_, grid, measured.depth_m, color_rgb, !frame.color.empty(),
                             differenceOptions(config_), &difference_ms);
  if (device_ms != nullptr) *device_ms = raycast_ms + difference_ms;
  KeyframeScore score = scoreSamples(samples, frame, config_, per_sample);
  if (rendered != nullptr) *rendered = std::move(samples);
  if (differences != nullptr) *differences = std::move(per_sample);
  return score;
}

}  // namespace strata::selection
