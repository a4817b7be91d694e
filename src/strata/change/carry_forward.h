#pragma once
// Carrying observations forward into a session that did not look again.
// Change detection compares each session's own layer M_i with the static map, so an object that
// stands in session i as it stood before shows up in session i only if session i fused frames of
// it. Keyframe selection skips exactly those frames: they agree with the map. What a keyframe
// confirmed (surface points where its measured depth agrees with the map) is known from the
// selection's raycast, fused or not, so the session's layer can take, around those points, the
// latest observed values of earlier sessions where it has none of its own: the session then
// holds the object it saw as it was.
// Cost: two layer copies per session between device and host (the layer is edited on the host).
// A carried voxel keeps its weight, so S, merged with the session, counts that observation
// twice (capped at max_weight); its value does not change.
//
// Rule, per voxel within `radius_m` of a confirmed point: where the session's layer is unobserved
// (weight below min_weight) and `latest` is observed, the session's voxel becomes latest's
// (distance, weight, colour). Observed voxels of the session are never touched, so what the
// session fused itself always wins.
// Thread safe (pure functions).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "strata/change/skipped_keyframe_evidence.h"
#include "strata/map/tsdf_map.h"

namespace strata::change {

/// A surface point a keyframe confirmed, world frame, and the radius it vouches for
/// (select/confirmed_points.h: enough to reach the next samples of its keyframe).
struct ConfirmedPoint {
  Eigen::Vector3f p_W = Eigen::Vector3f::Zero();
  float radius_m = 0.0f;
};

struct CarryStats {
  std::size_t points = 0;  // confirmed points given
  std::size_t voxels = 0;  // voxels taken from `latest`
};

/// Fills `session` (see the rule above). `latest` and `session` must have the same voxel size
/// (InputError otherwise). Blocks are allocated in `session` where a voxel is carried. Voxels in
/// *own (when non-null) are never carried into: the session has evidence of its own there below
/// min_weight (free space seen through a vacated place, skipped_keyframe_evidence.h), and the
/// latest observation is exactly what that evidence contradicts.
CarryStats carryObserved(const TsdfMap& latest, const std::vector<ConfirmedPoint>& points,
                         float min_weight, TsdfMap& session, const VoxelSet* own = nullptr);

/// After a session ended: its observed voxels (weight >= min_weight) replace latest's, so latest
/// holds, per voxel, the last session that observed it.
void keepLatestObserved(const TsdfMap& session, float min_weight, TsdfMap& latest);

}  // namespace strata::change
