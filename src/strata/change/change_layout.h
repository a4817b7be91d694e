#pragma once
// Host mirror of the change-detection push constants (shaders/change_*.comp), pinned with
// static_assert.
#include <cstddef>
#include <cstdint>

namespace strata::change::gpu {

/// change_difference.comp, change_session_dynamic.comp, change_static_update.comp.
struct ChangeVoxelPush {
  std::uint64_t static_address;   // S, a TSDF layer
  std::uint64_t session_address;  // M, a TSDF layer
  std::uint64_t label_address;    // a label layer: written, or read (D in the static update)
                                // (the dynamic row mask is a binding, see change_voxel_access.glsl)
  std::uint32_t voxel_count;    // allocated slots * 512
  std::uint32_t counter_index;  // counters[counter_index] += dynamic labels written
  float min_weight;
  float threshold_m;
  float merge_close_m;
  float max_weight;
};
static_assert(sizeof(ChangeVoxelPush) == 48 && offsetof(ChangeVoxelPush, voxel_count) == 24,
              "ChangeVoxelPush layout");

/// change_erode.comp, change_dilate.comp (the kernel edge is specialization constant 0; erosion
/// works on row masks only and ignores the addresses).
struct ChangeMorphPush {
  std::uint64_t raw_address;  // raw label layer (each voxel's own label), dilation
  std::uint64_t out_address;  // label layer written, dilation
  std::uint32_t block_count;
  std::uint32_t mask;  // DilationMask (dilation only)
  std::uint32_t counter_index;
  std::uint32_t pad0;
};
static_assert(sizeof(ChangeMorphPush) == 32 && offsetof(ChangeMorphPush, block_count) == 16,
              "ChangeMorphPush layout");

/// change_block_neighbours.comp.
struct ChangeNeighboursPush {
  std::uint64_t pool_address;  // unused (tsdf_sample.glsl's push block)
  std::uint32_t entry_count;
  std::uint32_t hash_mask;
  std::uint32_t slot_count;
  float voxel_size_m;  // unused
  float min_weight;    // unused
  std::uint32_t pad0;
};
static_assert(sizeof(ChangeNeighboursPush) == 32, "ChangeNeighboursPush layout");

}  // namespace strata::change::gpu
