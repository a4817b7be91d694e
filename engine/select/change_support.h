#pragma once
// Views of vacated places for change detection. The change detector
// trusts a voxel of a session's layer only from `views` fused frames on (its min_weight with
// constant weights). When an object leaves a place, the keyframes that look through it are
// selected (the map's surface lies in front of what they measure), but often one or two of them:
// the place never turns free in the static map, and the object's earlier instances are never
// segmented; a thin object's removal may not get a keyframe selected at all. This step adds,
// greedily, the keyframe whose rays pass the most vacated points that have fewer than `views` fused
// rays through them, until none has or no keyframe passes enough. The added keyframes are counted
// as fused images, not as keyframes worth reconstructing.
//
// Vacated points: on the sample rays that hit the map (of every keyframe, or only the selected
// ones), the map's surface point where the keyframe measures more than `depth_tolerance_m`
// beyond it.
// A keyframe passes a point when the point projects into its image in front of the camera and
// its measured depth there lies more than `depth_tolerance_m` beyond the point's depth (and
// within the fusion's range).
// Measured on the office (60 keyframes per session, with carry_forward.h): points of the selected
// keyframes only: 6 keyframes added (42.9 -> 45.0 % of the images), change detection over every
// instance 16 of 25; of every keyframe: 21 added (51.3 %), 19 of 25. The demo leaves the step off
// (`--change-views` turns it on): integrating the free space the skipped keyframes' vacated
// samples saw (change/carry_free.h) finds 20 of 25 with no keyframe added (42.9 %; arrivals 8
// of 9 against 7), and both together found 19 of 25 with 51.2 % (with the earlier free-space
// rule, bands around the samples' cells).
// Thread safe (pure functions).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "change/carry_free.h"
#include "core/types.h"
#include "select/select_samples.h"

namespace strata::selection {

struct SupportConfig {
  /// Fused rays every vacated point should have (0 switches the step off).
  int views = 3;
  /// A keyframe is added only when it passes at least this many points short of views: ~1 % of
  /// the 10 px grid; fewer are depth edges and thin parts, not a place worth a keyframe.
  int min_points = 30;
  /// Measured depth beyond a point by more than this passes it (sensor noise at 4 m plus the
  /// selection map's voxel).
  float depth_tolerance_m = 0.1f;
  /// Measured depth beyond this passes nothing: fusion does not use it (MapConfig::max_depth_m).
  float max_depth_m = 5.0f;
  /// A sample is a vacated point only when at least this many of its 8 grid neighbours look
  /// beyond the map's surface too: a vacated place is an area, while silhouettes under pose
  /// noise give lines of single samples (0: every such sample counts). Office: 3 drops 21 -> 15
  /// added views (51.3 -> 48.8 % of the images) and the same 19 of 25 instances found, but the
  /// thin parts of a removed chair go too (its coverage 0.46 -> 0.11), so the default keeps all.
  int min_neighbours = 0;
  /// Vacated points of every keyframe, not only the selected ones. A removed thin object (a
  /// chair) changes the depth of few samples, so the keyframes that look through its place are
  /// often not selected at all (office, session 3: no keyframe that sees through a removed
  /// chair's place was selected), and the place would never turn free.
  bool all_keyframes = true;

  void validate() const;  // InputError naming the field
};

/// The vacated points of one scored keyframe, world frame. `samples`: its raycast; `frame`: its
/// depth and pose.
std::vector<Eigen::Vector3f> vacatedPoints(const SampleRaycast& samples, const RgbdFrame& frame,
                                           const CameraIntrinsics& intrinsics,
                                           const SupportConfig& config);

/// The samples of one scored keyframe that disagree with the map, with its pose and no depth yet
/// (tiles of the grid's stride): those that look beyond the map's surface (vacated; the vacated
/// points' samples before any min_neighbours filter) and those that measure a surface in front of
/// it, or where the ray meets none (arrived; within max_depth_m, beyond the tolerance). Change
/// detection can integrate what they saw without fusing the keyframe (change/carry_free.h) once
/// change::keepDepthAround kept the depth around them; the selection loop does that only for the
/// keyframes it skips.
change::ChangedView changedView(const SampleRaycast& samples, const RgbdFrame& frame,
                                const SupportConfig& config);

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
                               const CameraIntrinsics& intrinsics, const SupportConfig& config,
                               int stride_px);

/// Whether a ray of `frame` passes `point_W` (see above).
bool passesPoint(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                 const Eigen::Vector3f& point_W, const SupportConfig& config);

struct SupportResult {
  std::vector<std::uint8_t> added;     // keyframes added as views (not selected before)
  std::size_t points = 0;              // vacated points (of every keyframe or the selected ones)
  std::size_t unsupported_before = 0;  // ... passed by fewer than `views` selected keyframes
  std::size_t unsupported_after = 0;   // ... by fewer than `views` selected or added ones
};

/// `vacated_points[k]`: vacatedPoints of keyframe k (of selected ones only unless all_keyframes);
/// `frames`: every keyframe of the session (depth and pose); `selected`: the selection.
SupportResult supportViews(const std::vector<std::vector<Eigen::Vector3f>>& vacated_points,
                           const std::vector<RgbdFrame>& frames, const CameraIntrinsics& intrinsics,
                           const std::vector<std::uint8_t>& selected, const SupportConfig& config);

}  // namespace strata::selection
