#version 450
// view_gain_block_table: the map's blocks in a box as a dense table (block -> pool slot, -1 where
// not allocated), so that view_gain.comp finds a block with one load instead of a hash probe per
// block its rays enter. The host fills the table with -1 first.
// Workgroup: 64 x 1 x 1, one invocation per hash-table entry; groups laid out 2D (x up to 65535).
// Bindings: 0 HashEntry entries[] (TSDF block hash), 1 int block_slots[] (x fastest over the box).
// Push constants: BlockTablePush (engine/explore/view_gain_kernel.cpp).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) writeonly buffer BlockSlots { int block_slots[]; };

layout(push_constant, std430) uniform Push {
  int box_lo_x, box_lo_y, box_lo_z;
  int box_nx, box_ny, box_nz;
  uint entry_count;
  uint groups_x;
} pc;

void main() {
  uint e = (gl_WorkGroupID.y * pc.groups_x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
  if (e >= pc.entry_count) return;
  uint64_t key = entries[e].key;
  if (key == kEmptyBlockKey) return;
  ivec3 b = unpackBlockKey(key) - ivec3(pc.box_lo_x, pc.box_lo_y, pc.box_lo_z);
  if (any(lessThan(b, ivec3(0))) || any(greaterThanEqual(b, ivec3(pc.box_nx, pc.box_ny, pc.box_nz)))) {
    return;
  }
  block_slots[b.x + pc.box_nx * (b.y + pc.box_ny * b.z)] = int(entries[e].slot);
}
