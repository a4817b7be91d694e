#version 450
// change_erode: step 3, erosion on dynamic row masks (change_rows.glsl): a raw dynamic
// voxel stays dynamic when at least half of the kernel^3 cube around it is raw dynamic
// (erodedLabel in engine/kernels/change_rules.h; voxels that fail become static, which the
// dilation reads from the raw labels).
// Reference: engine/kernels/change_reference.cpp (erodeReference).
// Workgroup: 256 x 1 x 1: 4 allocated slots per workgroup, one invocation per row of 8 voxels.
// Bindings: 0 uint counters[] (counters[counter_index] += dynamic voxels kept),
//           1 int neighbour_slots[] (27 per slot), 2 uint raw_mask[] (read),
//           3 uint eroded_mask[] (written, 64 words per slot), 4 uint near_dynamic[] (per slot,
//           zeroed by the host before: set for every block within one block of a kept voxel, so
//           the dilation skips the rest).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(block_count / 4).
// Specialization constant 0: the kernel edge in voxels (odd, <= 7).
// Push constants: ChangeMorphPush (engine/kernels/change_layout.h); addresses unused.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 256) in;
layout(constant_id = 0) const int kKernel = 3;

layout(std430, binding = 0) buffer Counters { uint counters[]; };
layout(std430, binding = 1) readonly buffer Neighbours { int neighbour_slots[]; };
layout(std430, binding = 2) readonly buffer RawMask { uint raw_mask[]; };
layout(std430, binding = 3) writeonly buffer ErodedMask { uint eroded_mask[]; };
layout(std430, binding = 4) buffer NearDynamic { uint near_dynamic[]; };

layout(push_constant, std430) uniform Push {
  uint64_t raw_address;
  uint64_t out_address;
  uint block_count;
  uint mask;
  uint counter_index;
  uint pad0;
} pc;

uint maskRow(uint word) { return raw_mask[word]; }

#include "change_rows.glsl"
#include "change_count.glsl"

void main() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  uint slot = group * 4u + gl_LocalInvocationIndex / kRowsPerBlock;
  uint row = gl_LocalInvocationIndex % kRowsPerBlock;
  uint kept = 0u;
  uint raw = slot < pc.block_count ? raw_mask[slot * kRowsPerBlock + row] : 0u;
  int y = int(row % 8u), z = int(row / 8u);
  // The cube is counted only around the row's dynamic voxels (few rows have any).
  for (uint bits = raw; bits != 0u; bits &= bits - 1u) {
    int x = findLSB(bits);
    uint n = 0u;
    for (int dz = -kRadius; dz <= kRadius; ++dz) {
      for (int dy = -kRadius; dy <= kRadius; ++dy) {
        n += bitCount(windowBits(extendedRow(slot, y + dy, z + dz), x));
      }
    }
    if (2u * n >= uint(kKernel * kKernel * kKernel)) kept |= 1u << uint(x);
  }
  if (slot < pc.block_count) eroded_mask[slot * kRowsPerBlock + row] = kept;
  if (kept != 0u) {  // rare: flag the 3x3x3 blocks whose dilation may reach a kept voxel
    for (uint n = 0u; n < 27u; ++n) {
      int neighbour = neighbour_slots[slot * 27u + n];
      if (neighbour >= 0) atomicOr(near_dynamic[neighbour], 1u);
    }
  }
  countDynamic(uint(bitCount(kept)), pc.counter_index);
}
