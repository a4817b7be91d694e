#version 450
// allocate_blocks: insert every block crossed by the truncation band around each valid depth
// sample into the block hash table, and list each touched block once for this pass.
// Reference: engine/kernels/block_allocation.cpp (allocateBlocksReference).
// Workgroup: 16 x 16 x 1, one invocation per pixel.
// Bindings: 0 HashEntry entries[] (coherent), 1 MapCounters, 2 uint touched_entries[],
//           3 float depth_m[] (row-major).
// Push constants: AllocatePush (engine/kernels/device_layout.h).
// NOTE: a pass is idempotent for the table: the host re-runs it with a new pass id after growing
// the table or the touched list, so nothing is dropped when either fills.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "camera.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) buffer Counters { MapCounters counters; };
layout(std430, binding = 2) writeonly buffer Touched { uint touched_entries[]; };
layout(std430, binding = 3) readonly buffer Depth { float depth_m[]; };

layout(push_constant, std430) uniform Push {
  mat4 T_W_C;
  vec4 K;
  uvec2 image_size;
  float min_depth_m;
  float max_depth_m;
  float truncation_m;
  float block_size_m;
  uint hash_mask;
  uint pass_id;
  uint touched_capacity;
  uint free_space_stride;  // > 0: every stride-th pixel (both axes) also allocates its free space
  uint pad1;
  uint pad2;
} pc;

void markTouched(uint e) {
  if (entries[e].touched_stamp == pc.pass_id) return;  // cheap early-out, most pixels stop here
  if (atomicExchange(entries[e].touched_stamp, pc.pass_id) != pc.pass_id) {
    uint i = atomicAdd(counters.touched_count, 1u);
    if (i < pc.touched_capacity) touched_entries[i] = e;
  }
}

void insertBlock(ivec3 block) {
  if (!blockInRange(block)) return;
  uint64_t key = packBlockKey(block);
  uint e = hashBlockKey(key) & pc.hash_mask;
  for (uint probe = 0u; probe < kMaxHashProbes; ++probe) {
    uint64_t seen = entries[e].key;
    if (seen == key) { markTouched(e); return; }
    if (seen == kEmptyBlockKey) {
      uint64_t previous = atomicCompSwap(entries[e].key, kEmptyBlockKey, key);
      if (previous == kEmptyBlockKey) {
        entries[e].slot = atomicAdd(counters.block_count, 1u);
        markTouched(e);
        return;
      }
      if (previous == key) { markTouched(e); return; }
    }
    e = (e + 1u) & pc.hash_mask;
  }
  atomicAdd(counters.hash_failures, 1u);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.image_size))) return;
  float depth = depth_m[pixel.y * pc.image_size.x + pixel.x];
  if (!depthValid(depth, pc.min_depth_m, pc.max_depth_m)) return;

  vec3 ray_C = pixelRay(vec2(pixel), pc.K);
  float range_m = depth * length(ray_C);
  vec3 dir_W = mat3(pc.T_W_C) * normalize(ray_C);
  vec3 origin_W = pc.T_W_C[3].xyz;
  float t_start = max(range_m - pc.truncation_m, 0.0);
  float t_end = range_m + pc.truncation_m;
  // Free space (for the ESDF: planners need distances away from surfaces too): on a sparse pixel
  // grid, the whole ray from the near limit is allocated; blocks are 8 voxels wide, so a stride of
  // a few pixels still reaches every block the view crosses at working ranges.
  if (pc.free_space_stride > 0u && pixel.x % pc.free_space_stride == 0u &&
      pixel.y % pc.free_space_stride == 0u) {
    t_start = min(t_start, pc.min_depth_m * length(ray_C));
  }

  // Amanatides-Woo traversal of the block grid along [t_start, t_end].
  vec3 start_b = (origin_W + dir_W * t_start) / pc.block_size_m;
  ivec3 block = ivec3(floor(start_b));
  ivec3 end_block = ivec3(floor((origin_W + dir_W * t_end) / pc.block_size_m));
  ivec3 step_dir = ivec3(sign(dir_W));
  vec3 inv_dir = 1.0 / max(abs(dir_W), vec3(1e-12));
  vec3 next_boundary = vec3(block) + max(vec3(step_dir), vec3(0.0));
  vec3 t_max = abs(next_boundary - start_b) * inv_dir * pc.block_size_m + t_start;
  vec3 t_delta = inv_dir * pc.block_size_m;
  int max_steps = 3 * (int(ceil((t_end - t_start) / pc.block_size_m)) + 2);
  for (int s = 0; s < max_steps; ++s) {
    insertBlock(block);
    if (block == end_block) break;
    if (t_max.x < t_max.y && t_max.x < t_max.z) {
      if (t_max.x > t_end) break;
      block.x += step_dir.x; t_max.x += t_delta.x;
    } else if (t_max.y < t_max.z) {
      if (t_max.y > t_end) break;
      block.y += step_dir.y; t_max.y += t_delta.y;
    } else {
      if (t_max.z > t_end) break;
      block.z += step_dir.z; t_max.z += t_delta.z;
    }
  }
}
