#version 450
// occupancy_allocate: insert into the block hash table the blocks that hold voxels a ray will
// update, so the mark pass finds them all. Two walks (push constant walk_blocks):
//   1 (every frame): the same segment scaled to block units, one step per block: 8x fewer steps.
//     Rounding at a block corner can make it skip a block the voxel walk enters; the mark pass
//     counts such ray segments and the host then runs
//   0 (rare fallback): the mark pass's own voxel traversal (occupancy_ray.glsl), exact by
//     construction, and marks again.
// Reference: engine/kernels/occupancy_reference.cpp (blocks allocated as voxels are marked).
// Workgroup: 16 x 16 x 1, one invocation per ray (pixel on the strided grid).
// Bindings: 0 HashEntry entries[] (coherent), 1 MapCounters, 2 float depth_m[] (row-major).
// Push constants: OccupancyRayPush (engine/kernels/occupancy_layout.h).
// NOTE: idempotent; the host re-runs it after growing the table when an insert found no entry.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "occupancy_ray.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) coherent buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) buffer Counters { MapCounters counters; };
layout(std430, binding = 2) readonly buffer Depth { float depth_m[]; };

void insertBlock(ivec3 block) {
  if (!blockInRange(block)) return;
  uint64_t key = packBlockKey(block);
  uint e = hashBlockKey(key) & pc.hash_mask;
  for (uint probe = 0u; probe < kMaxHashProbes; ++probe) {
    uint64_t seen = entries[e].key;
    if (seen == key) return;
    if (seen == kEmptyBlockKey) {
      uint64_t previous = atomicCompSwap(entries[e].key, kEmptyBlockKey, key);
      if (previous == kEmptyBlockKey) {
        entries[e].slot = atomicAdd(counters.block_count, 1u);
        return;
      }
      if (previous == key) return;
    }
    e = (e + 1u) & pc.hash_mask;
  }
  atomicAdd(counters.hash_failures, 1u);
}

// Every block the scaled segment crosses, the endpoint's too (an unused extra block stays
// unobserved).
void walkBlocks(OccupancyRay ray) {
  for (;;) {
    insertBlock(ray.voxel);  // cells are blocks here
    if (ray.voxel == ray.end_voxel) return;
    occupancyRayAdvance(ray);
  }
}

// Exactly the blocks of the voxels the mark pass updates.
void walkVoxels(OccupancyRay ray) {
  ivec3 last_block = ivec3(0x7fffffff);
  for (;;) {
    bool at_end = ray.voxel == ray.end_voxel;
    if (at_end && !ray.hit) return;
    ivec3 block = ray.voxel >> 3;  // arithmetic shift: floor division by the block edge
    if (block != last_block) {
      insertBlock(block);
      last_block = block;
    }
    if (at_end) return;
    occupancyRayAdvance(ray);
  }
}

void main() {
  uvec2 pixel;
  if (!occupancyPixel(gl_GlobalInvocationID.xy, pixel)) return;
  float depth = depth_m[pixel.y * pc.image_size.x + pixel.x];
  OccupancyRay ray;
  if (!occupancyRayStart(vec2(pixel), depth, pc.walk_blocks != 0u ? 0.125 : 1.0, ray)) return;
  if (pc.walk_blocks != 0u) {
    walkBlocks(ray);
  } else {
    walkVoxels(ray);
  }
}
