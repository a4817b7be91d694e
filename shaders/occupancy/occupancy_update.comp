#version 450
// occupancy_update: second half of one scan's update. One workgroup per block listed by
// occupancy_mark; each marked voxel gets exactly one log-odds update (hit over miss), Eq. (2)-(3)
// of Hornung et al. 2013, and its marks are cleared (it stays observed).
// Reference: engine/kernels/occupancy_reference.cpp (applyMarks).
// Workgroup: 128 x 1 x 1, one invocation per 4 consecutive voxels (16-byte accesses, which
// stream about twice as fast as scalar ones on lavapipe); workgroup (x + y * 65535) = list entry.
// Bindings: 0 uint touched_slots[].
// Push constants: OccupancyUpdatePush (engine/kernels/occupancy_layout.h); both layers by address.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "occupancy_rules.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Touched { uint touched_slots[]; };

layout(push_constant, std430) uniform Push {
  uint64_t state_address;
  uint64_t log_odds_address;
  float l_hit;
  float l_miss;
  float l_min;
  float l_max;
  uint touched_count;
  uint pad0;
  uint pad1;
  uint pad2;
} pc;

layout(buffer_reference, std430, buffer_reference_align = 16) buffer Quads { uvec4 q[]; };

void main() {
  uint entry = gl_WorkGroupID.x + gl_WorkGroupID.y * 65535u;
  if (entry >= pc.touched_count) return;
  uint quad = touched_slots[entry] * uint(kVoxelsPerBlock / 4) + gl_LocalInvocationID.x;
  Quads states = Quads(pc.state_address);
  uvec4 state = states.q[quad];
  if (((state.x | state.y | state.z | state.w) & kOccupancyScanBits) == 0u) return;
  Quads log_odds = Quads(pc.log_odds_address);
  uvec4 bits = log_odds.q[quad];
  uvec4 updated;
  for (int i = 0; i < 4; ++i) {
    updated[i] = floatBitsToUint(occupancyUpdate(state[i], uintBitsToFloat(bits[i]), pc.l_hit,
                                                 pc.l_miss, pc.l_min, pc.l_max));
    state[i] = occupancyStateAfterUpdate(state[i]);
  }
  log_odds.q[quad] = updated;
  states.q[quad] = state;
}
