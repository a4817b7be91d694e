#version 450
// gather_touched_blocks: the block keys of the blocks touched by the last allocation pass, for
// consumers that update derived layers incrementally (DeviceFusion::lastTouchedBlocks, ESDF).
// Workgroup: 256 x 1 x 1, one invocation per touched block.
// Bindings: 0 HashEntry entries[], 1 uint touched_entries[], 2 MapCounters,
//           3 uint64_t keys_out[] (one per touched block, in list order).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(touched / 256).
// Push constants: none.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) readonly buffer Touched { uint touched_entries[]; };
layout(std430, binding = 2) readonly buffer Counters { MapCounters counters; };
layout(std430, binding = 3) writeonly buffer KeysOut { uint64_t keys_out[]; };

void main() {
  uint i = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 256u;
  if (i >= counters.touched_count) return;
  keys_out[i] = entries[touched_entries[i]].key;
}
