#version 450
// integrate_tsdf: projective TSDF update of every voxel of the blocks touched by this frame.
// Reference: engine/kernels/tsdf_integration.cpp (integrateVoxelReference is the same rule).
// Workgroup: 8 x 8 x 8, one workgroup per touched block, one invocation per voxel; each voxel is
// written by exactly one invocation per frame, so no atomics.
// Bindings: 0 HashEntry entries[], 1 uint touched_entries[], 2 float depth_m[],
//           3 uint color_rgb8[] (the frame's packed 8-bit RGB, 3 bytes per pixel, row-major,
//           padded to whole words; ignored unless kFlagHasColor), 4 MapCounters,
//           5 vec4 normal_C[] (estimate_normals output; used when kFlagPointToPlane).
// Dispatch: (min(n, 65535), ceil(n / 65535)) groups for n touched blocks; extra groups exit.
// Push constants: IntegratePush (engine/kernels/device_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "camera.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 8) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) readonly buffer Touched { uint touched_entries[]; };
layout(std430, binding = 2) readonly buffer Depth { float depth_m[]; };
layout(std430, binding = 3) readonly buffer Color { uint color_rgb8[]; };
layout(std430, binding = 4) readonly buffer Counters { MapCounters counters; };
layout(std430, binding = 5) readonly buffer Normals { vec4 normal_C[]; };

const uint kFlagWeightDropoff = 1u;
const uint kFlagHasColor = 2u;
const uint kFlagPointToPlane = 4u;
const uint kWeightConstant = 0u;

layout(push_constant, std430) uniform Push {
  mat4 T_C_W;
  vec4 K;
  uvec2 image_size;
  float min_depth_m;
  float max_depth_m;
  float voxel_size_m;
  float truncation_m;
  float max_weight;
  float dropoff_start_m;
  uint64_t pool_address;
  uint weight_mode;
  uint flags;
} pc;

// The pixel's colour as r | g << 8 | b << 16 (packRgb) from the packed RGB bytes.
uint pixelColor(uint pixel) {
  uint byte_index = pixel * 3u;
  uint word = byte_index >> 2u;
  uint shift = (byte_index & 3u) * 8u;
  uint low = color_rgb8[word] >> shift;
  uint high = shift > 8u ? color_rgb8[word + 1u] << (32u - shift) : 0u;
  return (low | high) & 0xFFFFFFu;
}

uint blendColor(uint old_rgba, uint new_rgba, float old_weight, float weight) {
  vec3 old_c = vec3(old_rgba & 255u, (old_rgba >> 8) & 255u, (old_rgba >> 16) & 255u);
  vec3 new_c = vec3(new_rgba & 255u, (new_rgba >> 8) & 255u, (new_rgba >> 16) & 255u);
  vec3 c = (old_c * old_weight + new_c * weight) / (old_weight + weight);
  uvec3 q = uvec3(clamp(floor(c + 0.5), 0.0, 255.0));
  return q.x | (q.y << 8) | (q.z << 16);
}

void main() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  if (group >= counters.touched_count) return;
  uint entry = touched_entries[group];
  ivec3 block = unpackBlockKey(entries[entry].key);
  uint slot = entries[entry].slot;
  ivec3 local = ivec3(gl_LocalInvocationID);
  vec3 p_W = (vec3(block * kBlockEdge + local) + 0.5) * pc.voxel_size_m;
  vec3 p_C = (pc.T_C_W * vec4(p_W, 1.0)).xyz;
  if (p_C.z <= 0.0) return;

  vec2 uv = vec2(pc.K.x * p_C.x / p_C.z + pc.K.z, pc.K.y * p_C.y / p_C.z + pc.K.w);
  vec2 pixel_f = floor(uv + 0.5);
  if (pixel_f.x < 0.0 || pixel_f.y < 0.0 || pixel_f.x >= float(pc.image_size.x) ||
      pixel_f.y >= float(pc.image_size.y)) return;
  uint pixel = uint(pixel_f.y) * pc.image_size.x + uint(pixel_f.x);
  float depth = depth_m[pixel];
  if (!depthValid(depth, pc.min_depth_m, pc.max_depth_m)) return;

  // Distance along the ray through the voxel: (depth - z) scaled by |ray| at z = 1. It decides
  // which voxels are updated (the band behind the surface), whichever distance is stored.
  float ray_sdf_m = (depth - p_C.z) * length(vec3(p_C.xy / p_C.z, 1.0));
  if (ray_sdf_m < -pc.truncation_m) return;
  float sdf_m = ray_sdf_m;
  vec4 normal = normal_C[pixel];
  if ((pc.flags & kFlagPointToPlane) != 0u && normal.w > 0.5) {
    // Distance to the plane of the observed surface point (see DistanceMode::kPointToPlane).
    vec3 surface_C = pixelRay(pixel_f, pc.K) * depth;
    sdf_m = dot(normal.xyz, p_C - surface_C);
  }
  float tsdf_m = min(sdf_m, pc.truncation_m);

  float weight = pc.weight_mode == kWeightConstant ? 1.0 : 1.0 / (depth * depth);
  if ((pc.flags & kFlagWeightDropoff) != 0u && sdf_m < -pc.dropoff_start_m) {
    weight *= (pc.truncation_m + sdf_m) / (pc.truncation_m - pc.dropoff_start_m);
  }
  if (!(weight > 0.0)) return;

  TsdfBlockRef voxels = tsdfBlock(pc.pool_address, slot);
  uint v = uint(local.x + kBlockEdge * (local.y + kBlockEdge * local.z));
  TsdfVoxel voxel = voxels.voxels[v];
  float new_weight = voxel.weight + weight;
  voxel.tsdf_m = (voxel.tsdf_m * voxel.weight + tsdf_m * weight) / new_weight;
  if ((pc.flags & kFlagHasColor) != 0u) {
    voxel.color_rgba = blendColor(voxel.color_rgba, pixelColor(pixel), voxel.weight, weight);
  }
  voxel.weight = min(new_weight, pc.max_weight);
  voxels.voxels[v] = voxel;
}
