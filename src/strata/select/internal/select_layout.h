#pragma once
// Host mirror of the push constants of shaders/raycast_samples.comp (keyframe selection).
#include <cstddef>
#include <cstdint>

namespace strata::gpu {

struct SampleRaycastPush {
  float T_W_C[16];
  float K[4];  // fx, fy, cx, cy
  std::uint32_t grid_size[2];
  float min_depth_m;
  float max_depth_m;
  float voxel_size_m;
  float truncation_m;
  std::uint32_t hash_mask;
  float min_weight;
  std::uint64_t pool_address;
  std::uint32_t max_steps;
  std::uint32_t stride_px;
};
static_assert(sizeof(SampleRaycastPush) == 128 &&
                  offsetof(SampleRaycastPush, pool_address) == 112 &&
                  offsetof(SampleRaycastPush, stride_px) == 124,
              "SampleRaycastPush layout");

/// Bit 31 of a sample's colour word: the ray hit the map.
inline constexpr std::uint32_t kSampleHitBit = 0x80000000u;
/// Bit 30: the keyframe measured depth at the sample (the surface check ran).
inline constexpr std::uint32_t kSampleMeasuredBit = 0x40000000u;
/// Bit 29: the map holds the measured point (|interpolated TSDF| <= tolerance).
inline constexpr std::uint32_t kSampleHeldBit = 0x20000000u;

}  // namespace strata::gpu

namespace strata::gpu {

/// Push constants of shaders/sample_differences.comp.
struct SampleDifferencePush {
  std::uint32_t grid_size[2];
  float depth_tolerance_m;
  float max_depth_difference_m;
  std::uint32_t has_color;
};
static_assert(sizeof(SampleDifferencePush) == 20, "SampleDifferencePush layout");

}  // namespace strata::gpu
