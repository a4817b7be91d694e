#version 450
// allocate_blocks: insert into the block hash table every block that the truncation band of a
// valid depth sample may reach, and list each touched block once for this pass.
// Reference: engine/integrate/block_allocation.cpp (allocatedBlocksReference), operation for
// operation. One invocation per tile of kTilePx x kTilePx pixels: where the tile's depths span at
// most max_slab_depth_m, the blocks of the tile's frustum slab [z_min - truncation, z_max +
// truncation] are inserted (a superset of the blocks its pixels' band rays cross, see
// docs/integrate.md); otherwise each quarter of the tile is tried the same way, and a quarter that
// still spans too much marches each pixel's band ray through the block grid.
// Workgroup: 8 x 8 x 1 tiles.
// Bindings: 0 HashEntry entries[] (coherent), 1 MapCounters, 2 uint touched_entries[],
//           3 float depth_m[] (row-major), 4 uint quarter_range[] (estimate_normals.comp).
// Push constants: AllocatePush (engine/map/device_layout.h).
// NOTE: a pass is idempotent for the table: the host re-runs it with a new pass id after growing
// the table or the touched list, so nothing is dropped when either fills.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "camera.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) buffer Counters { MapCounters counters; };
layout(std430, binding = 2) writeonly buffer Touched { uint touched_entries[]; };
layout(std430, binding = 3) readonly buffer Depth { float depth_m[]; };
layout(std430, binding = 4) readonly buffer QuarterRange { uint quarter_range[]; };

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
  float max_slab_depth_m;  // a tile (or quarter) whose depths span more marches its rays
  uint pad;
} pc;

const uint kTilePx = 8u;       // gpu::kAllocationTilePx
const uint kQuarterPx = 4u;
const float kSlabMarginBlocks = 1e-3;  // keeps blocks within rounding of the slab's faces

void markTouched(uint e) {
  if (entries[e].touched_stamp == pc.pass_id) return;  // cheap early-out, most blocks stop here
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

// Amanatides-Woo traversal of the block grid along the pixel's ray over range [t_start, t_end].
void marchRay(uvec2 pixel, float depth, bool free_space) {
  vec3 ray_C = pixelRay(vec2(pixel), pc.K);
  float range_m = depth * length(ray_C);
  vec3 dir_W = mat3(pc.T_W_C) * normalize(ray_C);
  vec3 origin_W = pc.T_W_C[3].xyz;
  float t_start = max(range_m - pc.truncation_m, 0.0);
  float t_end = range_m + pc.truncation_m;
  if (free_space) t_start = min(t_start, pc.min_depth_m * length(ray_C));
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

// Inward unit normal of the side face through the camera centre and the rays a, b; oriented so
// that the slab's centre ray lies inside. Zero for a degenerate face (it then excludes nothing).
vec3 sideNormal(vec3 a, vec3 b, vec3 centre) {
  vec3 n = cross(a, b);
  float len = length(n);
  if (!(len > 0.0)) return vec3(0.0);
  n = n / len;
  return dot(n, centre) < 0.0 ? -n : n;
}

// Every block that meets the frustum slab of pixels [p0, p1] (inclusive) between camera depths
// z_near and z_far: the slab's world box gives the candidates, its six faces reject those wholly
// outside one of them.
void insertSlab(uvec2 p0, uvec2 p1, float z_min, float z_max) {
  float z_near = max(z_min - pc.truncation_m, 0.0);
  float z_far = z_max + pc.truncation_m;
  vec3 r00 = pixelRay(vec2(p0), pc.K);
  vec3 r10 = pixelRay(vec2(p1.x, p0.y), pc.K);
  vec3 r01 = pixelRay(vec2(p0.x, p1.y), pc.K);
  vec3 r11 = pixelRay(vec2(p1), pc.K);
  mat3 R_W_C = mat3(pc.T_W_C);
  vec3 origin_W = pc.T_W_C[3].xyz;
  vec3 lo = vec3(3.0e38);
  vec3 hi = vec3(-3.0e38);
  for (int i = 0; i < 4; ++i) {
    vec3 r = i == 0 ? r00 : (i == 1 ? r10 : (i == 2 ? r01 : r11));
    vec3 near_W = R_W_C * (r * z_near) + origin_W;
    vec3 far_W = R_W_C * (r * z_far) + origin_W;
    lo = min(lo, min(near_W, far_W));
    hi = max(hi, max(near_W, far_W));
  }
  float margin_m = kSlabMarginBlocks * pc.block_size_m;
  ivec3 b_lo = ivec3(floor((lo - margin_m) / pc.block_size_m));
  ivec3 b_hi = ivec3(floor((hi + margin_m) / pc.block_size_m));

  vec3 centre_C = (r00 + r11) * 0.5;
  vec3 n_C[4] = vec3[4](sideNormal(r00, r10, centre_C), sideNormal(r10, r11, centre_C),
                        sideNormal(r11, r01, centre_C), sideNormal(r01, r00, centre_C));
  vec3 n_W[6];
  float d_W[6];
  for (int i = 0; i < 4; ++i) {
    n_W[i] = R_W_C * n_C[i];
    d_W[i] = -dot(n_W[i], origin_W);
  }
  vec3 axis_W = R_W_C[2];
  n_W[4] = axis_W;
  d_W[4] = -z_near - dot(axis_W, origin_W);
  n_W[5] = -axis_W;
  d_W[5] = z_far + dot(axis_W, origin_W);

  float half_m = 0.5 * pc.block_size_m;
  for (int z = b_lo.z; z <= b_hi.z; ++z) {
    for (int y = b_lo.y; y <= b_hi.y; ++y) {
      for (int x = b_lo.x; x <= b_hi.x; ++x) {
        vec3 centre_W = (vec3(x, y, z) + 0.5) * pc.block_size_m;
        bool inside = true;
        for (int f = 0; f < 6 && inside; ++f) {
          vec3 n = n_W[f];
          float reach = half_m * (abs(n.x) + abs(n.y) + abs(n.z));
          inside = dot(n, centre_W) + d_W[f] + reach >= -margin_m;
        }
        if (inside) insertBlock(ivec3(x, y, z));
      }
    }
  }
}

bool freeSpacePixel(uvec2 pixel) {
  return pc.free_space_stride > 0u && pixel.x % pc.free_space_stride == 0u &&
         pixel.y % pc.free_space_stride == 0u;
}

void main() {
  uvec2 tile = gl_GlobalInvocationID.xy;
  uvec2 p0 = tile * kTilePx;
  if (any(greaterThanEqual(p0, pc.image_size))) return;
  uvec2 p1 = min(p0 + kTilePx, pc.image_size) - 1u;
  uvec2 tiles = (pc.image_size + (kTilePx - 1u)) / kTilePx;
  uint first = 4u * (tile.y * tiles.x + tile.x);
  uint second_half = 4u * tiles.x * tiles.y;

  // Free-space rays on the sparse pixel grid.
  if (pc.free_space_stride > 0u) {
    uint s = pc.free_space_stride;
    for (uint v = (p0.y + s - 1u) / s * s; v <= p1.y; v += s) {
      for (uint u = (p0.x + s - 1u) / s * s; u <= p1.x; u += s) {
        float depth = depth_m[v * pc.image_size.x + u];
        if (depthValid(depth, pc.min_depth_m, pc.max_depth_m)) marchRay(uvec2(u, v), depth, true);
      }
    }
  }

  // Depth range of each quarter (estimate_normals.comp); empty quarters have lo > hi.
  vec2 range[4];
  for (uint q = 0u; q < 4u; ++q) {
    uint lo = quarter_range[first + q];
    uint hi = quarter_range[second_half + first + q];
    range[q] = lo > hi ? vec2(3.0e38, -3.0e38) : vec2(uintBitsToFloat(lo), uintBitsToFloat(hi));
  }
  vec2 whole = vec2(min(min(range[0].x, range[1].x), min(range[2].x, range[3].x)),
                    max(max(range[0].y, range[1].y), max(range[2].y, range[3].y)));
  if (whole.x > whole.y) return;  // no valid depth
  if (whole.y - whole.x <= pc.max_slab_depth_m) {
    insertSlab(p0, p1, whole.x, whole.y);
    return;
  }
  for (uint q = 0u; q < 4u; ++q) {
    if (range[q].x > range[q].y) continue;
    uvec2 q0 = p0 + uvec2((q & 1u) * kQuarterPx, (q >> 1u) * kQuarterPx);
    uvec2 q1 = min(q0 + (kQuarterPx - 1u), p1);
    if (range[q].y - range[q].x <= pc.max_slab_depth_m) {
      insertSlab(q0, q1, range[q].x, range[q].y);
      continue;
    }
    for (uint v = q0.y; v <= q1.y; ++v) {
      for (uint u = q0.x; u <= q1.x; ++u) {
        float depth = depth_m[v * pc.image_size.x + u];
        if (depthValid(depth, pc.min_depth_m, pc.max_depth_m)) marchRay(uvec2(u, v), depth, false);
      }
    }
  }
}
