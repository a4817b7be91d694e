#pragma once
// Ground truth of keyframe selection on a simulated world, computed from the simulator
// only, never from the method's outputs.
//
// A keyframe of session N >= 1 is worth reconstructing (positive) when at least
// `min_positive_fraction` (default 2 %) of its valid pixels (measured depth > 0: what the mapper
// receives) see change or unmapped space:
//  - change: the pixel's object id is one whose state differs from session N-1 (moved or added;
//    SessionTruth::since_previous), or the surface the map last observed along the pixel's ray
//    (the first surface in the world of the latest session whose fused keyframes saw it:
//    MapHistory) lies more than `surface_tolerance_m` (5 cm) from the true surface now (covers
//    removed objects: the wall or floor they hid is uncovered; moved objects' old and new places;
//    and changes of an earlier session that no fused keyframe of it looked at);
//  - unmapped: the map built so far does not hold the true surface point (exact depth from the
//    true pose): its voxels there are unobserved (weight below min_weight, or no block), or their
//    interpolated distance is more than `held_tolerance_voxels` (2) of the map's voxels from zero
//    (observed only as free space, or a thin part the map lost).
// The 2 % default is ~6,000 pixels at 640x480, a 0.35 m object at 2.5 m, and ~60 samples of the
// 10 px selection grid. Pixels are looked at on a grid (every `pixel_stride` px); the fraction is
// unbiased. Frames: poses T_W_C take camera to world coordinates; lengths in metres. Thread safe
// (pure functions on const inputs).
#include <vector>

#include "strata/core/types.h"
#include "strata/map/tsdf_map.h"
#include "strata/select/eval/map_history.h"
#include "strata/sim/ray_scene.h"
#include "strata/sim/sensors/rgbd_camera.h"

namespace strata::selection {

struct TruthConfig {
  /// Share of valid pixels that must see change or unmapped space.
  double min_positive_fraction = 0.02;
  /// A surface moved by more than this counts as changed (sensor noise at 4 m is ~2 cm).
  float surface_tolerance_m = 0.05f;
  /// Every n-th pixel on both axes is looked at.
  int pixel_stride = 4;
  /// The map holds a true surface point when its interpolated distance there is within this many
  /// of its voxels of zero.
  float held_tolerance_voxels = 2.0f;
  /// Voxel weight from which the map counts a voxel as observed.
  float min_weight = 1.0f;

  void validate() const;  // InputError naming the field
};

struct KeyframeTruth {
  int valid_pixels = 0;     // looked-at pixels with measured depth
  int changed_pixels = 0;   // ... that see change
  int unmapped_pixels = 0;  // ... whose true surface is not in the map
  int positive_pixels = 0;  // ... either
  double positive_fraction = 0.0;
  bool positive = false;
};

/// Truth of one keyframe. `frame` is the simulator's render of the keyframe at `true_T_W_C`;
/// `changed_ids` the objects changed since the previous session; `history` the sessions the map
/// was built from; `map` the map built so far (host copy).
KeyframeTruth keyframeTruth(const sim::SimulatedFrame& frame, const Eigen::Isometry3d& true_T_W_C,
                            const CameraIntrinsics& intrinsics, const std::vector<int>& changed_ids,
                            const MapHistory& history, const TsdfMap& map,
                            const TruthConfig& config = {});

/// Share of the true surface points seen in `frame` (valid pixels on the grid) that `map` has
/// observed: the coverage of a map, for comparing the incremental and the complete map.
struct SurfaceCoverage {
  long long points = 0;
  long long observed = 0;
  double ratio() const { return points > 0 ? static_cast<double>(observed) / points : 0.0; }
};
void addSurfaceCoverage(const sim::SimulatedFrame& frame, const Eigen::Isometry3d& true_T_W_C,
                        const CameraIntrinsics& intrinsics, const TsdfMap& map,
                        const TruthConfig& config, SurfaceCoverage& coverage);

}  // namespace strata::selection
