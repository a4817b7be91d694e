#version 450
// change_block_neighbours: for every allocated block, the pool slots of the 3x3x3 blocks around it
// (itself included; -1 where unallocated), so erosion and dilation reach across block borders
// without probing the hash table per voxel.
// Workgroup: 64 x 1 x 1, one invocation per hash-table entry.
// Bindings: 0 HashEntry entries[] (read), 1 int neighbour_slots[] (27 per slot, neighbour n at
//           block offset (n % 3, n / 3 % 3, n / 9) - 1).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(entry_count / 64).
// Push constants: ChangeNeighboursPush (engine/kernels/change_layout.h); pool_address,
// voxel_size_m and min_weight are unused here but tsdf_sample.glsl (findBlockSlot) expects them.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) writeonly buffer Neighbours { int neighbour_slots[]; };

layout(push_constant, std430) uniform Push {
  uint64_t pool_address;
  uint entry_count;
  uint hash_mask;
  uint slot_count;
  float voxel_size_m;
  float min_weight;
  uint pad0;
} pc;

#include "tsdf_sample.glsl"

void main() {
  uint e = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 64u;
  if (e >= pc.entry_count) return;
  uint64_t key = entries[e].key;
  uint slot = entries[e].slot;
  if (key == kEmptyBlockKey || slot >= pc.slot_count) return;
  ivec3 block = unpackBlockKey(key);
  for (int n = 0; n < 27; ++n) {
    ivec3 offset = ivec3(n % 3, (n / 3) % 3, n / 9) - 1;
    neighbour_slots[slot * 27u + uint(n)] = findBlockSlot(block + offset);
  }
}
