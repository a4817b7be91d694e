#version 450
// integrate_args: the group counts of this frame's integrate_tsdf and gather_touched_blocks
// dispatches, from the allocation pass's counters, so one submission runs the whole frame.
// When the pass overflowed (hash insert failures, a full touched list, slots beyond the pool)
// both counts are zero: nothing is integrated, and the host grows what filled and runs the frame
// again (allocation is idempotent). Reference: DeviceFusion (the host rule it replaces).
// Workgroup: 1 x 1 x 1, one invocation.
// Bindings: 0 MapCounters, 1 uint args[8]: [0..2] integrate groups (x, y, 1),
//           [4..6] gather groups (x, y, 1).
// Push constants: uint touched_capacity, uint block_capacity.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = 0) readonly buffer Counters { MapCounters counters; };
layout(std430, binding = 1) writeonly buffer Args { uint args[]; };

layout(push_constant, std430) uniform Push {
  uint touched_capacity;
  uint block_capacity;
} pc;

const uint kMaxGroupsPerDimension = 65535u;

uvec2 groupsFor(uint n) {
  if (n == 0u) return uvec2(0u, 1u);
  uint x = min(n, kMaxGroupsPerDimension);
  return uvec2(x, (n + x - 1u) / x);
}

void main() {
  uint touched = counters.touched_count;
  bool overflow = counters.hash_failures > 0u || touched > pc.touched_capacity ||
                  counters.block_count > pc.block_capacity;
  if (overflow) touched = 0u;
  uvec2 integrate_groups = groupsFor(touched);
  uvec2 gather_groups = groupsFor((touched + 255u) / 256u);
  args[0] = integrate_groups.x;
  args[1] = integrate_groups.y;
  args[2] = 1u;
  args[3] = 0u;
  args[4] = gather_groups.x;
  args[5] = gather_groups.y;
  args[6] = 1u;
  args[7] = 0u;
}
