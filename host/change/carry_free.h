#pragma once
// Free space seen through vacated places by skipped keyframes (issue 6 with issue 5).
// When an object leaves, the keyframes that look through its old place measure beyond the map's
// surface there. The change detector turns that place free in the static map only from
// min_weight fused frames on; selection fuses few of those keyframes (a removed chair changes
// few samples), so the object's earlier instances stay unsegmented. The selection's raycast has
// already compared every keyframe's depth with the map on its sample grid: where a sample looks
// beyond the surface, the keyframe saw free space around that surface. This step integrates that
// free space into the session's change-detection layer, one observation per keyframe, as fusing
// the keyframe would there, but from its vacated samples only (a 10 px grid: at most 1 % of its
// pixels), so a place turns free only where min_weight keyframes saw through it.
//
// Rule, per view (one skipped keyframe) and per voxel, at most once per view: the voxel's centre
// projects into the cell of one of its vacated samples (within cell_px / 2 of the sample's pixel
// in u and v) at a camera z within band_m of the map's surface depth there and at least the
// truncation distance in front of the measured depth (so its truncated distance is +truncation,
// whatever the surface behind). It then takes one free observation as constant-weight fusion
// would: tsdf = (tsdf * w + truncation) / (w + 1), w = min(w + 1, max_weight); colour kept.
// Only the band around the old surface is updated: that is where an earlier session's layer holds
// the object, and it bounds the work.
// Thread safe (pure functions).
#include <Eigen/Geometry>
#include <cstddef>
#include <unordered_set>
#include <vector>

#include "core/types.h"
#include "map/tsdf_map.h"

namespace strata::change {

/// One sample of a keyframe that looks beyond the map's surface (camera z, metres).
struct VacatedSample {
  float u_px = 0.0f;
  float v_px = 0.0f;
  float surface_m = 0.0f;   // the map's surface (rendered depth)
  float measured_m = 0.0f;  // the keyframe's depth, beyond the surface
};

/// A keyframe's vacated samples and pose.
struct VacatedView {
  Eigen::Isometry3f T_W_C = Eigen::Isometry3f::Identity();
  std::vector<VacatedSample> samples;
};

struct FreeSpaceConfig {
  /// Side of a sample's cell: the sample grid's stride.
  float cell_px = 10.0f;
  /// Half depth of the updated band around the map's surface: the change layer's truncation
  /// (8 cm at 2 cm voxels) plus the selection map's voxel (5 cm), for where its surface lies.
  float band_m = 0.13f;

  void validate() const;  // InputError naming the field
};

/// Global voxel indices (the same type as block indices, so the map's block hash serves).
using VoxelSet = std::unordered_set<GlobalVoxelIndex, BlockIndexHash>;

struct FreeSpaceStats {
  std::size_t views = 0;    // views given
  std::size_t samples = 0;  // their vacated samples
  std::size_t voxels = 0;   // voxel observations added (a voxel counts once per view)
};

/// Integrates the free space of `views` into `session` (see the rule above); `intrinsics`: the
/// keyframes' camera. Voxels updated are added to *updated when non-null. Blocks are allocated in
/// `session` where a voxel is updated.
FreeSpaceStats integrateFreeSpace(const std::vector<VacatedView>& views,
                                  const CameraIntrinsics& intrinsics, const FreeSpaceConfig& config,
                                  TsdfMap& session, VoxelSet* updated = nullptr);

}  // namespace strata::change
