#version 450
// estimate_normals: per-pixel surface normal of the depth image in the camera frame, from central
// differences of the back-projected neighbours, oriented toward the camera (used by the
// point-to-plane signed distance of integrate_tsdf); and the depth range of every quarter tile
// (4 x 4 pixels) for allocate_blocks, so that pass reads 8 numbers per tile instead of 64 depths.
// Reference: engine/integrate/normal_estimation.cpp (estimateNormalsReference); the ranges are
// the plain minimum and maximum of the quarter's valid depths (allocatedBlocksReference).
// Workgroup: 16 x 16 x 1, one invocation per pixel.
// Bindings: 0 float depth_m[], 1 vec4 normal_C[] (xyz unit normal, w = 1 valid / 0 invalid),
//           2 uint quarter_range[]: [4 t + q] the bits of quarter q's smallest depth of tile t,
//           [4 T + 4 t + q] the bits of its largest (T tiles; positive floats order as uints; the
//           host fills the first half with 0xFFFFFFFF and the second with 0 before the pass).
// Push constants: vec4 K, uvec2 image_size, float min_depth_m, max_depth_m, max_relative_jump,
//                 uint flags (1: write normals), uint tiles_x, uint tile_count.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_vote : require
#include "camera.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Depth { float depth_m[]; };
layout(std430, binding = 1) writeonly buffer Normals { vec4 normal_C[]; };
layout(std430, binding = 2) buffer QuarterRange { uint quarter_range[]; };

layout(push_constant, std430) uniform Push {
  vec4 K;
  uvec2 image_size;
  float min_depth_m;
  float max_depth_m;
  float max_relative_jump;
  uint flags;
  uint tiles_x;
  uint tile_count;
} pc;

const uint kFlagNormals = 1u;
const uint kTilePx = 8u;  // gpu::kAllocationTilePx

#include "normal_stencil.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  bool inside = all(lessThan(pixel, pc.image_size));
  uint lo = 0xFFFFFFFFu;
  uint hi = 0u;
  if (inside) {
    if ((pc.flags & kFlagNormals) != 0u) {
      normal_C[pixel.y * pc.image_size.x + pixel.x] = pixelNormal(ivec2(pixel));
    }
    float depth = depthAt(ivec2(pixel));
    if (depthValid(depth, pc.min_depth_m, pc.max_depth_m)) {
      lo = floatBitsToUint(depth);
      hi = lo;
    }
  }
  // The 4 invocations of a quarter-tile row reduce among themselves, so one atomic pair per run
  // reaches memory. That needs subgroup lanes in local-index order (every driver known here does
  // it; the spec does not promise it): a subgroup that is not falls back to one pair per pixel.
  uint own_lo = lo;
  uint own_hi = hi;
  bool in_order = subgroupAll(gl_SubgroupInvocationID == gl_LocalInvocationIndex % gl_SubgroupSize);
  lo = min(lo, subgroupShuffleXor(lo, 1u));
  hi = max(hi, subgroupShuffleXor(hi, 1u));
  lo = min(lo, subgroupShuffleXor(lo, 2u));
  hi = max(hi, subgroupShuffleXor(hi, 2u));
  if (!in_order) {
    lo = own_lo;
    hi = own_hi;
  }
  if (!inside || (in_order && (pixel.x & 3u) != 0u) || lo > hi) return;
  uvec2 tile = pixel / kTilePx;
  uvec2 in_tile = pixel % kTilePx;
  uint q = 4u * (tile.y * pc.tiles_x + tile.x) + (in_tile.x >= kTilePx / 2u ? 1u : 0u) +
           (in_tile.y >= kTilePx / 2u ? 2u : 0u);
  atomicMin(quarter_range[q], lo);
  atomicMax(quarter_range[4u * pc.tile_count + q], hi);
}
