#version 450
// change_dilate: step 3, dilation: dilatedLabel(raw, eroded dynamic voxels in the
// kernel^3 cube, mask) for the 8 voxels of a row, the cube tested on eroded row masks
// (change_rules.h; change_rows.glsl).
// Reference: engine/kernels/change_reference.cpp (dilateReference).
// Workgroup: 256 x 1 x 1: 4 allocated slots per workgroup, one invocation per row of 8 voxels.
// Bindings: 0 uint counters[] (counters[counter_index] += dynamic labels written),
//           1 int neighbour_slots[] (27 per slot), 2 uint eroded_mask[] (read),
//           3 uint raw_labels[] (read), 4 uint out_labels[] (written), 5 uint near_dynamic[]
//           (per slot, from the erosion: 0 where no eroded dynamic voxel is within a block).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(block_count / 4).
// Specialization constants: 0 the kernel edge in voxels (odd, <= 7), 1 label layers by device
// address instead of bindings 3-4 (layers beyond one binding's range).
// Push constants: ChangeMorphPush (engine/kernels/change_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "change_layout.glsl"
#include "change_rules.glsl"

layout(local_size_x = 256) in;
layout(constant_id = 0) const int kKernel = 5;
layout(constant_id = 1) const bool kByAddress = false;

layout(std430, binding = 0) buffer Counters { uint counters[]; };
layout(std430, binding = 1) readonly buffer Neighbours { int neighbour_slots[]; };
layout(std430, binding = 2) readonly buffer ErodedMask { uint eroded_mask[]; };
layout(std430, binding = 3) readonly buffer RawLabels { uint raw_labels[]; };
layout(std430, binding = 4) writeonly buffer OutLabels { uint out_labels[]; };
layout(std430, binding = 5) readonly buffer NearDynamic { uint near_dynamic[]; };

layout(push_constant, std430) uniform Push {
  uint64_t raw_address;
  uint64_t out_address;
  uint block_count;
  uint mask;
  uint counter_index;
  uint pad0;
} pc;

uint maskRow(uint word) { return eroded_mask[word]; }

#include "change_rows.glsl"
#include "change_count.glsl"

uint loadRaw(uint i) { return kByAddress ? Labels(pc.raw_address).v[i] : raw_labels[i]; }

void storeOut(uint i, uint label) {
  if (kByAddress) {
    Labels(pc.out_address).v[i] = label;
  } else {
    out_labels[i] = label;
  }
}

// Bit x: an eroded dynamic voxel lies in the cube around voxel x of row (y, z).
uint dynamicNearRow(uint slot, int y, int z) {
  uint any_row = 0u;
  for (int dz = -kRadius; dz <= kRadius; ++dz) {
    for (int dy = -kRadius; dy <= kRadius; ++dy) any_row |= extendedRow(slot, y + dy, z + dz);
  }
  uint near = 0u;
  for (int x = 0; x < kBlockEdge; ++x) {
    if (windowBits(any_row, x) != 0u) near |= 1u << uint(x);
  }
  return near;
}

void main() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  uint slot = group * 4u + gl_LocalInvocationIndex / kRowsPerBlock;
  uint row = gl_LocalInvocationIndex % kRowsPerBlock;
  uint dynamic_labels = 0u;
  if (slot < pc.block_count) {
    uint near = near_dynamic[slot] != 0u ? dynamicNearRow(slot, int(row % 8u), int(row / 8u)) : 0u;
    uint first = slot * uint(kVoxelsPerBlock) + row * uint(kBlockEdge);
    for (uint x = 0u; x < uint(kBlockEdge); ++x) {
      uint label = dilatedLabel(loadRaw(first + x), (near >> x) & 1u, pc.mask);
      storeOut(first + x, label);
      dynamic_labels += label == kLabelDynamic ? 1u : 0u;
    }
  }
  countDynamic(dynamic_labels, pc.counter_index);
}
