#version 450
// occupancy_mark: first half of one scan's update. Every ray marks the voxels it passes through
// (miss) and its endpoint (hit) in the state layer with atomicOr, so several rays meeting in a
// voxel leave one mark per kind; occupancy_update then applies one update per voxel (hit over
// miss), as OctoMap does per scan. Each block with a mark is listed once (stamp per slot).
// Reference: engine/kernels/occupancy_reference.cpp (markRay).
// Workgroup: 16 x 16 x 1, one invocation per ray (pixel on the strided grid).
// Bindings: 0 HashEntry entries[] (read), 1 OccupancyCounters, 2 float depth_m[],
//           3 uint block_stamp[] (per slot), 4 uint touched_slots[] (capacity >= block count),
//           5 uint state[] (the state label layer).
// Push constants: OccupancyRayPush (engine/kernels/occupancy_layout.h).
// Specialization constant 0: reach the state layer by device address (push constant) instead of
// binding 5, for layers beyond one binding's range (128 MiB on lavapipe).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "occupancy_ray.glsl"
#include "occupancy_rules.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) buffer Counters {
  uint touched_count;   // blocks listed in touched_slots this frame
  uint missing_blocks;  // ray segments whose block is not allocated (the block walk skipped it)
  uint reserved0;
  uint reserved1;
} counters;
layout(std430, binding = 2) readonly buffer Depth { float depth_m[]; };
layout(std430, binding = 3) coherent buffer Stamps { uint block_stamp[]; };
layout(std430, binding = 4) writeonly buffer Touched { uint touched_slots[]; };

layout(std430, binding = 5) coherent buffer State { uint state_words[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer StateWords { uint w[]; };
layout(constant_id = 0) const bool kByAddress = false;

const uint kNoSlot = 0xFFFFFFFFu;

uint findSlot(ivec3 block) {
  if (!blockInRange(block)) return kNoSlot;
  uint64_t key = packBlockKey(block);
  uint e = hashBlockKey(key) & pc.hash_mask;
  for (uint probe = 0u; probe < kMaxHashProbes; ++probe) {
    uint64_t seen = entries[e].key;
    if (seen == key) return entries[e].slot;
    if (seen == kEmptyBlockKey) break;
    e = (e + 1u) & pc.hash_mask;
  }
  return kNoSlot;
}

void listBlock(uint slot) {
  if (block_stamp[slot] == pc.frame_id) return;  // cheap early-out, most rays stop here
  if (atomicExchange(block_stamp[slot], pc.frame_id) != pc.frame_id) {
    touched_slots[atomicAdd(counters.touched_count, 1u)] = slot;
  }
}

void mark(uint slot, ivec3 voxel, uint bit) {
  ivec3 local = voxel & 7;
  uint index = slot * uint(kVoxelsPerBlock) + uint(local.x + 8 * (local.y + 8 * local.z));
  // Read first: most voxels near the camera are crossed by many rays and already marked.
  if (kByAddress) {
    StateWords state = StateWords(pc.state_address);
    if ((state.w[index] & bit) == 0u) atomicOr(state.w[index], bit);
  } else if ((state_words[index] & bit) == 0u) {
    atomicOr(state_words[index], bit);
  }
}

// Marks the ray's voxels inside its current block; false when the ray is done.
// NOTE: a loop per block inside the loop over blocks, so the hash lookup runs once per block: on
// lavapipe, code under a branch runs (masked) whenever any lane of the SIMD group takes it.
bool markBlock(inout OccupancyRay ray) {
  if (ray.voxel == ray.end_voxel && !ray.hit) return false;  // a cut ray's end is not updated
  ivec3 block = ray.voxel >> 3;
  uint slot = findSlot(block);
  if (slot == kNoSlot) {
    atomicAdd(counters.missing_blocks, 1u);
  } else {
    listBlock(slot);
  }
  for (;;) {
    bool at_end = ray.voxel == ray.end_voxel;
    if (at_end && !ray.hit) return false;
    if (slot != kNoSlot) {
      mark(slot, ray.voxel, at_end ? kOccupancyHitThisScan : kOccupancyMissThisScan);
    }
    if (at_end) return false;
    occupancyRayAdvance(ray);
    if ((ray.voxel >> 3) != block) return true;
  }
}

void main() {
  uvec2 pixel;
  if (!occupancyPixel(gl_GlobalInvocationID.xy, pixel)) return;
  OccupancyRay ray;
  float depth = depth_m[pixel.y * pc.image_size.x + pixel.x];
  if (!occupancyRayStart(vec2(pixel), depth, 1.0, ray)) return;
  while (markBlock(ray)) {
  }
}
