#pragma once
// Per-sample differences of keyframe selection: the rendered map (raycast_samples.comp)
// against the new keyframe, on the device (shaders/sample_differences.comp) and in a plain C++
// reference of the same semantics. The host takes the upper-half means of these
// (src/strata/select/keyframe_metrics.cpp), so the device does the per-sample work and the host sorts
// a few thousand numbers.
#include <vector>

#include "strata/core/types.h"
#include "strata/select/select_samples.h"
#include "strata/vk/vk.h"

namespace strata {

struct SampleDifferenceOptions {
  /// Depth differences up to this count as none (sensor noise plus voxelisation).
  float depth_tolerance_m = 0.05f;
  /// Depth differences are clipped here so one far outlier cannot dominate.
  float max_depth_difference_m = 0.5f;
};

struct SampleDifferences {
  /// Mean absolute chromaticity difference of the blurred images; -1 on a miss or without colour.
  std::vector<float> color;
  /// |new depth - rendered depth| beyond the tolerance, clipped; -1 on a miss or without new depth.
  std::vector<float> depth_m;
};

/// Host reference of sample_differences.comp. `frame` must have the depth size the grid was made
/// for (colour may be empty).
SampleDifferences sampleDifferencesReference(const SampleRaycast& rendered, const RgbdFrame& frame,
                                             const SampleDifferenceOptions& options);

/// Device per-sample differences, reading the samples the raycast kernel left on the device.
/// Buffers are kept between calls. Not thread safe.
class SampleDifferenceKernel {
 public:
  explicit SampleDifferenceKernel(vk::Context& context);
  /// `raycast` must have just run for the keyframe (its samples buffer holds `grid`'s samples);
  /// `depth_m` and `color_rgb` are the keyframe at the grid's pixels (keyframeAtSamples, gathered
  /// once by the caller, who also needs them for the surface check). The device time goes to
  /// *device_ms when non-null. Sizes other than the grid's throw InputError.
  SampleDifferences run(const SampleRaycastKernel& raycast, const SampleGrid& grid,
                        const std::vector<float>& depth_m,
                        const std::vector<std::uint32_t>& color_rgb, bool has_color,
                        const SampleDifferenceOptions& options, double* device_ms = nullptr);

 private:
  void ensureCapacity(std::size_t sample_count);
  vk::Context& context_;
  vk::ComputePipeline pipeline_;
  vk::Buffer keyframe_in_;
  vk::Buffer differences_out_;
  vk::TimestampQueries timer_;
  std::size_t capacity_ = 0;
};

/// The keyframe's depth (metres; 0 where invalid) and colour (r | g << 8 | b << 16; 0 without
/// colour) at the grid's pixels: what sample_differences.comp reads per sample.
void keyframeAtSamples(const SampleGrid& grid, const RgbdFrame& frame, std::vector<float>& depth_m,
                       std::vector<std::uint32_t>& color_rgb);

}  // namespace strata
