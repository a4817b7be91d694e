#pragma once
// Parameters and statistics of multi-session change detection (docs/change.md). The rules
// they parameterise are in change_rules.h.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "strata/map/map_config.h"

namespace strata::change {

struct ChangeConfig {
  /// Voxels of a layer with less weight are unobserved in that layer. Higher trusts only
  /// well-seen voxels (fewer false changes) but leaves more space unknown. The weight is the
  /// fusion's: change detection fuses with constant weights (apps::changeMapConfig), so this
  /// counts the frames of a full-rate (30 Hz) recording that saw the voxel; for a subsampled
  /// session use forSubsampling(). With 1/z^2 weights a voxel seen at 2 m gains only 0.25 a frame.
  float min_weight = 10.0f;
  /// Label dynamic where both layers are observed and |f_M - f_S| exceeds this (5-7 cm at 2 cm
  /// voxels). Lower finds smaller displacements but labels more noise. Also the margin by which a
  /// session must lie below S for its dynamic part.
  float difference_threshold_m = 0.05f;
  /// Erosion (noise removal): a dynamic label survives when at least half of this cube is dynamic.
  /// Odd, 1-7 voxels; larger removes bigger specks and thin parts of real changes.
  int erosion_kernel_voxels = 3;
  /// Dilation (shape recovery) with a larger cube. Odd, 1-7 voxels.
  int dilation_kernel_voxels = 5;
  /// Inside dynamic clusters, values within this of the static estimate are averaged instead of
  /// the larger one winning (0 <= merge_close < difference threshold).
  float merge_close_m = 0.02f;

  /// Throws InputError naming the bad field.
  void validate(float voxel_size_m) const;

  /// Fused frames that must see a voxel before it counts, with constant weights (one per frame).
  int minFrames() const { return std::max(1, static_cast<int>(std::ceil(min_weight))); }

  /// The same thresholds for sessions fused from one frame in every `recorded_per_fused` frames
  /// of their recording (a stride, or frames spread over a path): each fused frame stands for
  /// that many recorded views, so min_weight becomes min_weight / recorded_per_fused fused views.
  /// Throws InputError unless recorded_per_fused >= 1.
  ChangeConfig forSubsampling(double recorded_per_fused) const;
};

/// Time per stage of one session update: device time from timestamp queries on the device, host
/// wall time in reference mode.
struct ChangeStageTimes {
  double neighbours_ms = 0.0;       // neighbour-slot table for erosion/dilation (device only)
  double difference_ms = 0.0;       // D: |f_M - f_S| > theta
  double erosion_ms = 0.0;          // D: erosion
  double dilation_ms = 0.0;         // D: dilation
  double static_update_ms = 0.0;    // S merged with M_N
  double session_dynamic_ms = 0.0;  // the session's dynamic part against the new S (3 passes)
  double total() const {
    return neighbours_ms + difference_ms + erosion_ms + dilation_ms + static_update_ms +
           session_dynamic_ms;
  }
};

struct ChangeUpdateStats {
  int session = -1;
  ChangeStageTimes stages;
  double wall_ms = 0.0;                  // host wall time of the whole update
  std::uint32_t blocks = 0;              // allocated blocks each pass ran over
  std::uint64_t voxels = 0;              // blocks * 512
  std::uint64_t raw_dynamic_voxels = 0;  // D after differencing
  std::uint64_t eroded_dynamic_voxels = 0;
  std::uint64_t dynamic_voxels = 0;          // D after dilation
  std::uint64_t session_dynamic_voxels = 0;  // the session's dynamic part
};

/// The map change detection wants: `voxel_size_m`, free space allocated (without observed free
/// space, S cannot tell a new object from new static space) and constant weights (min_weight then
/// counts the frames that saw a voxel, whatever the range).
MapConfig changeMapConfig(float voxel_size_m);

}  // namespace strata::change
