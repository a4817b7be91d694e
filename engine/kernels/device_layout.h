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
  std::uint32_t pad[3];
};
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
  std::uint32_t pad[3];
};
static_assert(sizeof(NormalsPush) == 48, "NormalsPush layout");

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

inline void storeMatrix(const Mat4& m, float out[16]) {
  for (int i = 0; i < 16; ++i) out[i] = m.data()[i];
}

}  // namespace strata::gpu
