#version 450
// esdf_slot_keys: inverts the block hash table into slot -> block key, so the host learns which
// block every pool slot holds (DeviceEsdf keeps that list to plan updates).
// Workgroup: 256 x 1 x 1, one invocation per hash-table entry.
// Bindings: 0 HashEntry entries[] (read), 1 uint64_t slot_keys[] (written for every used entry;
//           slots without an entry keep what the host filled, kEmptyBlockKey).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(entry_count / 256).
// Push constants: uint entry_count, uint slot_capacity.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) writeonly buffer SlotKeys { uint64_t slot_keys[]; };

layout(push_constant, std430) uniform Push {
  uint entry_count;
  uint slot_capacity;
} pc;

void main() {
  uint e = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 256u;
  if (e >= pc.entry_count) return;
  uint64_t key = entries[e].key;
  uint slot = entries[e].slot;
  if (key != kEmptyBlockKey && slot < pc.slot_capacity) slot_keys[slot] = key;
}
