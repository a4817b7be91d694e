#pragma once
// Parameters of the OctoMap-style occupancy layer (Hornung et al., "OctoMap: an efficient
// probabilistic 3D mapping framework based on octrees", Auton. Robots 2013). Defaults are OctoMap's
// published ones. validate() throws InputError naming the field; every consumer calls it once.
#include <cstdint>
#include <string>

#include "strata/map/map_config.h"

namespace strata {

/// The probabilities of OccupancyConfig as log-odds, l(p) = log(p / (1 - p)), in float as the
/// kernels use them (computed once on the host, so device and reference add the same numbers).
struct OccupancyLogOdds {
  float hit = 0.0f;   // added to a voxel holding a ray's endpoint (> 0)
  float miss = 0.0f;  // added to a voxel a ray passes through (< 0)
  float min = 0.0f;   // clamping bounds, Eq. (3)
  float max = 0.0f;
  float occupied = 0.0f;  // occupied when log-odds >= this, free below it
};

struct OccupancyConfig {
  /// P(occupied | hit): how much one endpoint raises a voxel's occupancy. Higher commits faster
  /// to obstacles and takes more misses to clear them. OctoMap: 0.7 (l = +0.85).
  float prob_hit = 0.7f;
  /// P(occupied | ray passed through): below 0.5. Lower clears dynamic obstacles faster but erodes
  /// thin or grazing surfaces that rays skim. OctoMap: 0.4 (l = -0.41).
  float prob_miss = 0.4f;
  /// Clamping thresholds, Eq. (3): a voxel's probability stays in [min, max], so a voxel observed
  /// for long can still change state after a few contrary updates (bounded confidence).
  /// Wider bounds are more stable, narrower ones adapt faster. OctoMap: 0.12 / 0.97.
  float clamp_min_prob = 0.12f;
  float clamp_max_prob = 0.97f;
  /// A voxel is occupied when its probability is >= this, free below (if ever observed).
  float occupied_prob = 0.5f;
  /// Depth samples below this are invalid readings and cast no ray (metres, camera z).
  float min_depth_m = 0.1f;
  /// Rays end at this depth (metres, camera z; OctoMap's maxrange, here measured along the optical
  /// axis like MapConfig::max_depth_m): a sample beyond it marks free space up to it and no hit,
  /// because far returns are too noisy to place an obstacle. forMap() takes the map's max depth.
  float max_range_m = 5.0f;
  /// Every n-th pixel on both axes casts a ray (1 = every pixel, as OctoMap inserts a full cloud).
  /// Larger strides cost n^2 less but leave far voxels (where neighbour rays are more than a voxel
  /// apart) unobserved.
  std::uint32_t pixel_stride = 1;

  /// Defaults with the depth range of `map` (min_depth_m, max_range_m = max_depth_m).
  static OccupancyConfig forMap(const MapConfig& map);
  /// Throws InputError naming the bad field and the rule it breaks.
  void validate() const;
  /// log(p / (1 - p)) of each probability, in float.
  OccupancyLogOdds logOdds() const;
  std::string describe() const;
};

/// log(p / (1 - p)) in double, rounded to float once.
float logOddsOf(double probability);

}  // namespace strata
