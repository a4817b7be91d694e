#version 450
// esdf_query_points: planner queries on the ESDF for a batch of points: distance, gradient and
// status (trilinear over the 8 surrounding voxel centres when all are known), and optionally the
// sphere collision flag. Same semantics as the host queries (engine/kernels/esdf_query.h, whose
// header is the specification; esdf_query.cpp / esdf_query_collision.cpp are the reference).
// Workgroup: 128 x 1 x 1, one invocation per point; groups laid out 2D (x up to 65535) so any
// batch size fits the dispatch limits.
// Bindings: 0 HashEntry entries[] (TSDF block hash: block -> slot, shared with the ESDF pool),
//           1 vec4 points_W[] (xyz; host replaces non-finite points with a far sentinel),
//           2 vec4 samples_out[] (xyz gradient, w distance), 3 uint flags_out[]
//           (bits 0-1 status: 0 known, 1 unknown, 2 outside; bit 2 interpolated; bit 3 free),
//           4 EsdfVoxel esdf_pool[] (read through the binding when the pool fits one binding's
//           range: on lavapipe that took samples from ~5 to ~14 million/s on redkitchen; by
//           device address otherwise, e.g. pools over 128 MiB).
// Specialization constant 0: kPoolByAddress (1: read the pool by pc.esdf_pool_address).
// Push constants: EsdfQueryPush (engine/kernels/esdf_query_kernel.cpp).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "esdf_layout.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) readonly buffer Points { vec4 points_W[]; };
layout(std430, binding = 2) writeonly buffer Samples { vec4 samples_out[]; };
layout(std430, binding = 3) writeonly buffer Flags { uint flags_out[]; };
layout(std430, binding = 4) readonly buffer EsdfPool { EsdfVoxel esdf_pool[]; };
layout(constant_id = 0) const uint kPoolByAddress = 0u;

layout(push_constant, std430) uniform Push {
  uint64_t esdf_pool_address;
  uint64_t pool_address;  // TSDF pool: only tsdf_sample.glsl's (unused) TSDF helpers read it
  uint hash_mask;
  float voxel_size_m;
  float min_weight;       // only for tsdf_sample.glsl's (unused) TSDF helpers
  uint point_count;
  uint esdf_block_count;  // slots at or beyond it hold no computed ESDF: read as unallocated
  float sphere_radius_m;  // radius + margin; < 0: no sphere test
  float max_distance_m;
  uint policy;            // 0 unknown is occupied, 1 unknown is free
} pc;

#include "tsdf_sample.glsl"

const uint kStatusKnown = 0u;
const uint kStatusUnknown = 1u;
const uint kStatusOutside = 2u;
const float kMaxVoxelCoord = 8.0e6;  // kMaxVoxelCoord in esdf_query_lookup.h
const uint kScanUnknown = 0u;
const uint kScanObstacle = 1u;

int esdfSlot(ivec3 block) {
  int slot = findBlockSlot(block);
  return (slot < 0 || uint(slot) >= pc.esdf_block_count) ? -1 : slot;
}

EsdfVoxel esdfVoxel(int slot, ivec3 local) {
  uint v = uint(local.x + kBlockEdge * (local.y + kBlockEdge * local.z));
  if (kPoolByAddress != 0u) return esdfBlock(pc.esdf_pool_address, uint(slot)).voxels[v];
  return esdf_pool[uint(slot) * uint(kVoxelsPerBlock) + v];
}

uint readEsdf(ivec3 v, out float distance_m) {
  distance_m = 0.0;
  ivec3 block = blockOfVoxel(v);
  int slot = esdfSlot(block);
  if (slot < 0) return kStatusOutside;
  EsdfVoxel voxel = esdfVoxel(slot, v - block * kBlockEdge);
  if ((voxel.site_and_flags & kEsdfObservedBit) == 0u) return kStatusUnknown;
  distance_m = voxel.distance_m;
  return kStatusKnown;
}

bool voxelOf(vec3 p_W, out ivec3 v) {
  vec3 g = p_W / pc.voxel_size_m;
  v = ivec3(0);
  if (!all(lessThan(abs(g), vec3(kMaxVoxelCoord)))) return false;
  v = ivec3(floor(g));
  return true;
}

vec3 voxelCenter(ivec3 v) { return (vec3(v) + 0.5) * pc.voxel_size_m; }

// Trilinear distance and its gradient (unit-free) when all 8 neighbours are known.
bool interpolate(vec3 p_W, out float distance_m, out vec3 gradient) {
  vec3 g = p_W / pc.voxel_size_m - 0.5;
  vec3 base_f = floor(g);
  ivec3 base = ivec3(base_f);
  float v[8];
  distance_m = 0.0;
  gradient = vec3(0.0);
  for (int i = 0; i < 8; ++i) {
    ivec3 corner = base + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    if (readEsdf(corner, v[i]) != kStatusKnown) return false;
  }
  vec3 f = g - base_f;
  float x00 = v[0] * (1.0 - f.x) + v[1] * f.x;
  float x10 = v[2] * (1.0 - f.x) + v[3] * f.x;
  float x01 = v[4] * (1.0 - f.x) + v[5] * f.x;
  float x11 = v[6] * (1.0 - f.x) + v[7] * f.x;
  float y0 = x00 * (1.0 - f.y) + x10 * f.y;
  float y1 = x01 * (1.0 - f.y) + x11 * f.y;
  distance_m = y0 * (1.0 - f.z) + y1 * f.z;
  gradient.x = (1 - f.y) * (1 - f.z) * (v[1] - v[0]) + f.y * (1 - f.z) * (v[3] - v[2]) +
               (1 - f.y) * f.z * (v[5] - v[4]) + f.y * f.z * (v[7] - v[6]);
  gradient.y = (1 - f.x) * (1 - f.z) * (v[2] - v[0]) + f.x * (1 - f.z) * (v[3] - v[1]) +
               (1 - f.x) * f.z * (v[6] - v[4]) + f.x * f.z * (v[7] - v[5]);
  gradient.z = (1 - f.x) * (1 - f.y) * (v[4] - v[0]) + f.x * (1 - f.y) * (v[5] - v[1]) +
               (1 - f.x) * f.y * (v[6] - v[2]) + f.x * f.y * (v[7] - v[3]);
  gradient /= pc.voxel_size_m;
  return true;
}

// Is the voxel a scan target: unknown, or observed and a site or inside (kScanObstacle)?
bool isTarget(EsdfVoxel voxel, uint target) {
  bool observed = (voxel.site_and_flags & kEsdfObservedBit) != 0u;
  return target == kScanUnknown ? !observed : observed && voxel.distance_m < 0.5 * pc.voxel_size_m;
}

// An unallocated block is unknown throughout: is its voxel centre nearest to c within reach?
bool missingBlockReaches(ivec3 v_lo, ivec3 v_hi, vec3 c, float r2) {
  ivec3 nearest = clamp(ivec3(roundEven(c / pc.voxel_size_m - 0.5)), v_lo, v_hi);
  vec3 d = voxelCenter(nearest) - c;
  return dot(d, d) <= r2;
}

bool blockContains(int slot, ivec3 b, ivec3 v_lo, ivec3 v_hi, vec3 c, float r2, uint target) {
  for (int z = v_lo.z; z <= v_hi.z; ++z) {
    for (int y = v_lo.y; y <= v_hi.y; ++y) {
      for (int x = v_lo.x; x <= v_hi.x; ++x) {
        vec3 d = voxelCenter(ivec3(x, y, z)) - c;
        if (dot(d, d) <= r2 && isTarget(esdfVoxel(slot, ivec3(x, y, z) - b * kBlockEdge), target)) {
          return true;
        }
      }
    }
  }
  return false;
}

// Does a voxel centre within r of c hold the target? Visits the blocks of the ball's box.
bool ballContains(vec3 c, float r, uint target) {
  ivec3 lo = ivec3(ceil((c - r) / pc.voxel_size_m - 0.5));
  ivec3 hi = ivec3(floor((c + r) / pc.voxel_size_m - 0.5));
  if (any(greaterThan(lo, hi))) return false;
  float r2 = r * r;
  ivec3 block_lo = blockOfVoxel(lo);
  ivec3 block_hi = blockOfVoxel(hi);
  for (int bz = block_lo.z; bz <= block_hi.z; ++bz) {
    for (int by = block_lo.y; by <= block_hi.y; ++by) {
      for (int bx = block_lo.x; bx <= block_hi.x; ++bx) {
        ivec3 b = ivec3(bx, by, bz);
        ivec3 v_lo = max(lo, b * kBlockEdge);
        ivec3 v_hi = min(hi, b * kBlockEdge + (kBlockEdge - 1));
        int slot = esdfSlot(b);
        bool found = slot < 0 ? target == kScanUnknown && missingBlockReaches(v_lo, v_hi, c, r2)
                              : blockContains(slot, b, v_lo, v_hi, c, r2, target);
        if (found) return true;
      }
    }
  }
  return false;
}

bool sphereFree(vec3 c, float r) {
  if (!(r >= 0.0) || !(r < pc.max_distance_m)) return false;
  ivec3 v;
  if (!voxelOf(c, v)) return false;
  float d;
  if (readEsdf(v, d) == kStatusKnown) {
    // The ESDF is 1-Lipschitz: d(c) >= d(v) - |c - centre(v)|.
    if (!(d - length(c - voxelCenter(v)) > r)) return false;
    return pc.policy == 1u || !ballContains(c, r, kScanUnknown);
  }
  if (pc.policy == 0u) return false;
  return !ballContains(c, r, kScanObstacle);
}

void main() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= pc.point_count) return;
  vec3 p_W = points_W[i].xyz;
  ivec3 v;
  uint status = kStatusOutside;
  float distance_m = 0.0;
  vec3 gradient = vec3(0.0);
  bool interpolated = false;
  if (voxelOf(p_W, v)) status = readEsdf(v, distance_m);
  if (status == kStatusKnown) {
    float d;
    vec3 g;
    interpolated = interpolate(p_W, d, g);
    if (interpolated) {
      distance_m = d;
      gradient = g;
    }
  }
  bool free_sphere = pc.sphere_radius_m >= 0.0 && sphereFree(p_W, pc.sphere_radius_m);
  samples_out[i] = vec4(gradient, distance_m);
  flags_out[i] = status | (interpolated ? 4u : 0u) | (free_sphere ? 8u : 0u);
}
