#pragma once
// Keyframe selection by raycast reprojection (docs/select.md): the current map is
// raycast into a keyframe's pose on a sparse pixel grid and compared with the keyframe's own
// images.
//   coverage  m_c = samples whose ray hits the map / samples (where the keyframe has depth, only
//                   the samples with measured depth count: beyond its range nothing is new)
//   change    m_delta = mean of the upper half of the per-sample absolute differences of the
//                   blurred, colour-normalised (chromaticity: resists light changes) rendered and
//                   new images (the upper half, so a small changed region counts)
//   depth change  = the same statistic on |new depth - rendered depth| beyond a tolerance (metres),
//                   where depth exists
//   surface change = share of the samples with measured depth whose measured point the map does
//                   not hold (unobserved there, or its interpolated distance more than
//                   `held_tolerance_voxels` of its voxels from zero): new space and geometric
//                   change in one number, as a distance to the map's surface rather than along
//                   the ray, so grazing views of a mapped floor do not count
// plus the two image-similarity baselines (normalised cross-correlation, 10-bin histogram
// correlation). Along a trajectory the metrics are smoothed, thresholded and the selection dilated
// (keyframe_selection.h).
//
// This header is the stable API other components (the LCM mapper) call. Thread safety: a
// KeyframeScorer is not thread safe (one per thread); scoreSamples/scoreKeyframeReference are.
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/select/select_differences.h"
#include "strata/select/select_samples.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {
class DeviceTsdfMap;
}

namespace strata::selection {

struct ScorerConfig {
  /// Pixel step of the sample grid on both axes: 10 (the method's default) scores a 640x480 frame
  /// from 64x48 rays; 1 is dense (slower, barely more informative after the blur).
  int sample_stride_px = 10;
  /// Voxels lighter than this count as unobserved: rays pass through them (a map fused with
  /// constant weights counts frames).
  float min_weight = 1e-6f;
  /// Per-sample depth differences are clipped here so one far outlier cannot dominate the mean.
  float max_depth_difference_m = 0.5f;
  /// Depth differences up to this count as none: sensor noise (~2 cm at 4 m) plus the rendered
  /// surface's voxelisation. 5 cm is also what the ground truth calls a moved surface.
  float depth_tolerance_m = 0.05f;
  /// Surface check: the map holds a measured point within this many of its voxels (2 on a 5 cm
  /// map: 10 cm, sensor noise at 4 m plus the voxelisation of thin parts).
  float held_tolerance_voxels = 2.0f;
  /// Histogram baseline: bins of grey level.
  int histogram_bins = 10;
  /// TSDF layer of the device map keyframes are scored against (0: the default layer).
  int tsdf_layer = 0;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// The metrics of one keyframe against the map. Similarities are in [-1, 1] (1 = identical).
struct KeyframeScore {
  int samples = 0;              // grid samples in the image
  int hits = 0;                 // samples with measured depth (all without depth) hitting the map
  double coverage = 0.0;        // hits / samples with measured depth (all without depth)
  double color_change = 0.0;    // upper-half mean of normalised colour differences (~0..1)
  double depth_change_m = 0.0;  // upper-half mean of |depth difference| (0 without depth)
  double ncc = 0.0;             // baseline: normalised cross-correlation of grey images
  double histogram = 0.0;       // baseline: correlation of grey-level histograms
  double surface_change = 0.0;  // share of measured samples the map does not hold (0 w/o depth)
};

/// Metrics from the raycast samples and the keyframe's images: the host half of scoring, shared
/// by the device and reference paths so both decide alike from the same samples.
KeyframeScore scoreSamples(const SampleRaycast& rendered, const RgbdFrame& frame,
                           const ScorerConfig& config);
/// The same from per-sample differences already computed (on the device: KeyframeScorer).
KeyframeScore scoreSamples(const SampleRaycast& rendered, const RgbdFrame& frame,
                           const ScorerConfig& config, const SampleDifferences& differences);
/// The per-sample difference settings of a scorer config.
SampleDifferenceOptions differenceOptions(const ScorerConfig& config);

/// The surface-check input of a keyframe: its depth at the grid samples, tolerance in metres.
MeasuredSamples measuredSamples(const SampleGrid& grid, const RgbdFrame& frame,
                                const ScorerConfig& config, float voxel_size_m);

/// Host reference: raycastSamplesReference (with the surface check) + scoreSamples.
KeyframeScore scoreKeyframeReference(const TsdfMap& map, const RgbdFrame& frame,
                                     const CameraIntrinsics& intrinsics,
                                     const ScorerConfig& config = {},
                                     SampleRaycast* rendered = nullptr);

/// Scores keyframes against a device map (its TSDF layer 0): raycast_samples.comp, then
/// sample_differences.comp on the samples left on the device, then scoreSamples on the host
/// (coverage counts, upper-half means, the baselines).
class KeyframeScorer {
 public:
  /// `context` must outlive the scorer. Validates the config.
  KeyframeScorer(vk::Context& context, const ScorerConfig& config = {});

  /// Scores `frame` (pose T_W_C, depth and colour of `intrinsics`' size; colour may be empty:
  /// colour metrics are then 0) against `map`. Bad input throws InputError. `device_ms` (optional)
  /// receives the device time of both kernels; `rendered` (optional) the samples, `differences`
  /// (optional) the device's per-sample differences.
  KeyframeScore score(DeviceTsdfMap& map, const RgbdFrame& frame,
                      const CameraIntrinsics& intrinsics, double* device_ms = nullptr,
                      SampleRaycast* rendered = nullptr, SampleDifferences* differences = nullptr);

  const ScorerConfig& config() const { return config_; }
  /// Scores against TSDF layer `layer` of the maps passed to score() from now on.
  void setTsdfLayer(int layer) { config_.tsdf_layer = layer; }

 private:
  ScorerConfig config_;
  SampleRaycastKernel kernel_;
  SampleDifferenceKernel difference_kernel_;
};

}  // namespace strata::selection
