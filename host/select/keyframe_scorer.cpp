// Keyframe scoring on the device (raycast_samples.comp) and its host reference.
#include "select/keyframe_scorer.h"

#include "kernels/device_tsdf_map.h"

namespace strata::selection {
namespace {

RaycastOptions raycastOptions(const ScorerConfig& config) {
  RaycastOptions options;
  options.min_weight = config.min_weight;
  return options;
}

}  // namespace

KeyframeScore scoreKeyframeReference(const TsdfMap& map, const RgbdFrame& frame,
                                     const CameraIntrinsics& intrinsics, const ScorerConfig& config,
                                     SampleRaycast* rendered) {
  config.validate();
  validateFrame(frame, intrinsics);
  SampleRaycast samples = raycastSamplesReference(map, intrinsics, frame.T_W_C,
                                                  config.sample_stride_px, raycastOptions(config));
  KeyframeScore score = scoreSamples(samples, frame, config);
  if (rendered != nullptr) *rendered = std::move(samples);
  return score;
}

KeyframeScorer::KeyframeScorer(vk::Context& context, const ScorerConfig& config)
    : config_(config), kernel_(context) {
  config_.validate();
}

KeyframeScore KeyframeScorer::score(DeviceTsdfMap& map, const RgbdFrame& frame,
                                    const CameraIntrinsics& intrinsics, double* device_ms,
                                    SampleRaycast* rendered) {
  validateFrame(frame, intrinsics);
  SampleRaycast samples = kernel_.run(map, intrinsics, frame.T_W_C, config_.sample_stride_px,
                                      raycastOptions(config_), device_ms);
  KeyframeScore score = scoreSamples(samples, frame, config_);
  if (rendered != nullptr) *rendered = std::move(samples);
  return score;
}

}  // namespace strata::selection
