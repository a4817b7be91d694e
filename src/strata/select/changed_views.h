#pragma once
// The changed views of the keyframes that selection skips: the samples of a scored keyframe that
// disagree with the map (the map's surface in front of what it measures: something left; a
// surface measured in front of the map's: something arrived). Change detection integrates what
// those samples saw without fusing the keyframe (change/skipped_keyframe_evidence.h), so a place
// that few keyframes were selected for still turns free, and a small arrival still gets surface.
// Frames: T_W_C camera to world, depths along the camera's z, metres.
// Errors: InputError naming the field or the mismatched lengths.
// Thread safe (pure functions).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "strata/change/skipped_keyframe_evidence.h"
#include "strata/core/types.h"
#include "strata/select/select_samples.h"

namespace strata::selection {

struct ChangedViewConfig {
  /// A sample disagrees with the map where its measured depth lies more than this beyond or in
  /// front of the map's surface (sensor noise at 4 m plus the selection map's voxel).
  float depth_tolerance_m = 0.1f;
  /// Measured depth beyond this says nothing: fusion does not use it (MapConfig::max_depth_m).
  float max_depth_m = 5.0f;

  void validate() const;  // InputError naming the field
};

/// The samples of one scored keyframe that disagree with the map, with its pose and no depth yet
/// (tiles of the grid's stride): those that look beyond the map's surface (vacated) and those
/// that measure a surface in front of it, or where the ray meets none (arrived; within
/// max_depth_m, beyond the tolerance). Change detection integrates what they saw once
/// change::keepDepthAround kept the depth around them; the selection loop does that only for the
/// keyframes it skips.
change::ChangedView changedView(const SampleRaycast& samples, const RgbdFrame& frame,
                                const ChangedViewConfig& config);

/// Shares the vacated places among the keyframes of a session: a removed thin object leaves
/// vacated samples on few keyframes, and few of them where another keyframe looks through the same
/// place. For each keyframe k with targets[k], every vacated sample of every other view, as a
/// world point on the map's surface, that k passes (passesPoint) becomes a sample of views[k] too:
/// at the centre of the cell of stride_px it projects into, with its camera z as the surface
/// depth, once per cell and 10 cm of depth. No depth is kept here (change::keepDepthAround does,
/// once all samples are known). `views` and `frames`: one per keyframe, in order. Returns the
/// samples added.
std::size_t shareVacatedPlaces(std::vector<change::ChangedView>& views,
                               const std::vector<RgbdFrame>& frames,
                               const std::vector<std::uint8_t>& targets,
                               const CameraIntrinsics& intrinsics, const ChangedViewConfig& config,
                               int stride_px);

/// Whether a ray of `frame` passes `point_W`: the point projects into the image in front of the
/// camera and the depth measured there lies more than depth_tolerance_m beyond the point's (and
/// within max_depth_m).
bool passesPoint(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                 const Eigen::Vector3f& point_W, const ChangedViewConfig& config);

}  // namespace strata::selection
