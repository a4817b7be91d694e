#pragma once
// Host mirror of the occupancy kernels' push constants and counters (shaders/occupancy_*.comp,
// shaders/common/occupancy_ray.glsl), pinned with static_assert.
#include <cstddef>
#include <cstdint>

namespace strata::gpu {

/// occupancy_allocate and occupancy_mark.
struct OccupancyRayPush {
  float T_W_C[16];
  float K_inv[4];  // 1/fx, 1/fy, cx, cy
  std::uint32_t image_size[2];
  std::uint32_t pixel_stride;
  std::uint32_t hash_mask;
  float min_depth_m;
  float max_range_m;
  float inv_voxel_size;
  std::uint32_t frame_id;
  std::uint64_t state_address;
  std::uint32_t walk_blocks;  // occupancy_allocate: 1 = blocks, 0 = every voxel (exact)
  std::uint32_t pad;
};
static_assert(sizeof(OccupancyRayPush) == 128 && offsetof(OccupancyRayPush, min_depth_m) == 96 &&
                  offsetof(OccupancyRayPush, state_address) == 112,
              "OccupancyRayPush layout");

/// occupancy_update.
struct OccupancyUpdatePush {
  std::uint64_t state_address;
  std::uint64_t log_odds_address;
  float l_hit;
  float l_miss;
  float l_min;
  float l_max;
  std::uint32_t touched_count;
  std::uint32_t pad[3];
};
static_assert(sizeof(OccupancyUpdatePush) == 48 && offsetof(OccupancyUpdatePush, l_hit) == 16,
              "OccupancyUpdatePush layout");

/// Binding 1 of occupancy_mark.
struct OccupancyCounters {
  std::uint32_t touched_count;
  std::uint32_t missing_blocks;
  std::uint32_t reserved[2];
};
static_assert(sizeof(OccupancyCounters) == 16, "OccupancyCounters layout");

}  // namespace strata::gpu
