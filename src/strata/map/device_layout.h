#pragma once
// Host mirror of the std430 structs and push constants in shaders/ (pinned with static_assert).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

namespace strata::gpu {

struct HashEntry {
  std::uint64_t key;
  std::uint32_t slot;
  std::uint32_t touched_stamp;
};
static_assert(sizeof(HashEntry) == 16 && offsetof(HashEntry, slot) == 8, "HashEntry layout");

struct MapCounters {
  std::uint32_t block_count;
  std::uint32_t touched_count;
  std::uint32_t hash_failures;
  std::uint32_t reserved;
};
static_assert(sizeof(MapCounters) == 16, "MapCounters layout");

/// Column-major 4x4 float matrix as GLSL's mat4.
using Mat4 = Eigen::Matrix<float, 4, 4, Eigen::ColMajor>;

struct AllocatePush {
  float T_W_C[16];
  float K[4];  // fx, fy, cx, cy
  std::uint32_t image_size[2];
  float min_depth_m;
  float max_depth_m;
  float truncation_m;
  float block_size_m;
  std::uint32_t hash_mask;
  std::uint32_t pass_id;
  std::uint32_t touched_capacity;
  std::uint32_t free_space_stride;
  float max_slab_depth_m;  // a tile whose depths span more is split, then marched per pixel
  std::uint32_t pad;
};
/// allocate_blocks.comp: one invocation per tile of this many pixels on a side (8 x 8 tiles per
/// workgroup).
inline constexpr std::uint32_t kAllocationTilePx = 8;
static_assert(sizeof(AllocatePush) == 128 && offsetof(AllocatePush, truncation_m) == 96,
              "AllocatePush layout");

inline constexpr std::uint32_t kFlagWeightDropoff = 1u;
inline constexpr std::uint32_t kFlagHasColor = 2u;
inline constexpr std::uint32_t kFlagPointToPlane = 4u;

struct NormalsPush {
  float K[4];
  std::uint32_t image_size[2];
  float min_depth_m;
  float max_depth_m;
  float max_relative_jump;
  std::uint32_t flags;  // kNormalsFlagWrite: write normals (else only the quarter-tile ranges)
  std::uint32_t tiles_x;
  std::uint32_t tile_count;
};
static_assert(sizeof(NormalsPush) == 48, "NormalsPush layout");
inline constexpr std::uint32_t kNormalsFlagWrite = 1u;

struct IntegratePush {
  float T_C_W[16];
  float K[4];
  std::uint32_t image_size[2];
  float min_depth_m;
  float max_depth_m;
  float voxel_size_m;
  float truncation_m;
  float max_weight;
  float dropoff_start_m;
  std::uint64_t pool_address;
  std::uint32_t weight_mode;
  std::uint32_t flags;
};
static_assert(sizeof(IntegratePush) == 128 && offsetof(IntegratePush, pool_address) == 112,
              "IntegratePush layout");

struct RaycastPush {
  float T_W_C[16];
  float K[4];
  std::uint32_t image_size[2];
  float min_depth_m;
  float max_depth_m;
  float voxel_size_m;
  float truncation_m;
  std::uint32_t hash_mask;
  float min_weight;
  std::uint64_t pool_address;
  std::uint32_t max_steps;
  std::uint32_t pad0;
};
static_assert(sizeof(RaycastPush) == 128 && offsetof(RaycastPush, pool_address) == 112,
              "RaycastPush layout");

/// esdf_gather_sites.comp and esdf_scatter.comp.
struct EsdfBlockPush {
  std::uint64_t box_address;
  std::uint64_t tsdf_pool_address;
  std::uint64_t esdf_pool_address;
  std::uint32_t box_nx, box_ny, box_nz;
  std::uint32_t block_count;
  std::uint32_t first_block;
  float voxel_size_m;
  float site_threshold_m;
  float min_weight;
  float max_distance_m;
  std::uint32_t pad0;
};
static_assert(sizeof(EsdfBlockPush) == 64 && offsetof(EsdfBlockPush, box_nx) == 24 &&
                  offsetof(EsdfBlockPush, max_distance_m) == 56,
              "EsdfBlockPush layout");

/// esdf_edt_pass.comp.
struct EsdfEdtPush {
  std::uint64_t box_address;
  std::uint64_t reserved;
  std::uint32_t line_count;
  std::uint32_t first_line;
  std::uint32_t line_length;
  std::uint32_t lines_a;
  std::uint32_t stride_a;
  std::uint32_t stride_b;
  std::uint32_t stride_line;
  std::uint32_t axis;
  std::uint32_t max_d2;
  std::uint32_t first_a;
  std::uint32_t first_b;
  std::uint32_t pad0;
};
static_assert(sizeof(EsdfEdtPush) == 64 && offsetof(EsdfEdtPush, first_b) == 56,
              "EsdfEdtPush layout");

/// esdf_slot_keys.comp.
struct EsdfSlotKeysPush {
  std::uint32_t entry_count;
  std::uint32_t slot_capacity;
};
static_assert(sizeof(EsdfSlotKeysPush) == 8, "EsdfSlotKeysPush layout");

inline void storeMatrix(const Mat4& m, float out[16]) {
  for (int i = 0; i < 16; ++i) out[i] = m.data()[i];
}

}  // namespace strata::gpu
