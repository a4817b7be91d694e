#version 450
// raycast_samples: the raycast of raycast_tsdf on a sparse pixel grid, for keyframe selection
//: per sample the hit, the rendered depth and the voxel colour at the hit. Same march
// (raycast_march.glsl), so a grid with stride 1 matches raycast_tsdf pixel for pixel.
// Surface check: where the keyframe measured depth d (inside the map's fusion range) at the
// sample, the map's interpolated TSDF
// at the point d puts on the same ray; the map holds it when |TSDF| <= the tolerance. Unlike the
// rendered depth this is the distance to the map's surface, not along the ray, so a surface seen
// at a grazing angle is not taken for change.
// Sample (gx, gy) looks through pixel (offset + gx * stride, offset + gy * stride), offset =
// stride / 2 (integer division), so the grid is centred in the image.
// Reference: raycastSamplesReference (engine/kernels/select_samples_reference.cpp).
// Workgroup: 16 x 16 x 1, one invocation per sample.
// Bindings: 0 HashEntry entries[], 1 uvec2 samples_out[] (x = depth z in metres as float bits,
//           0 = miss; y = colour r | g << 8 | b << 16, bit 31 set on a hit, bit 30 where depth
//           was measured, bit 29 where the map holds the measured point), 2 Measured (the held
//           tolerance in metres, then the measured depth z per sample, 0 = none; the tolerance
//           rides here because the push constants already fill the 128 bytes every device has).
// Push constants: SampleRaycastPush (engine/kernels/select_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "camera.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) writeonly buffer SamplesOut { uvec2 samples_out[]; };
layout(std430, binding = 2) readonly buffer Measured {
  float held_tolerance_m;
  float measured_depth_m[];
};

layout(push_constant, std430) uniform Push {
  mat4 T_W_C;
  vec4 K;
  uvec2 grid_size;
  float min_depth_m;
  float max_depth_m;
  float voxel_size_m;
  float truncation_m;
  uint hash_mask;
  float min_weight;
  uint64_t pool_address;
  uint max_steps;
  uint stride_px;
} pc;

#include "tsdf_sample.glsl"
#include "raycast_march.glsl"

const uint kHitBit = 0x80000000u;
const uint kMeasuredBit = 0x40000000u;
const uint kHeldBit = 0x20000000u;

void main() {
  uvec2 g = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(g, pc.grid_size))) return;
  uvec2 pixel = uvec2(pc.stride_px / 2u) + g * pc.stride_px;

  vec3 ray_C = pixelRay(vec2(pixel), pc.K);
  float ray_scale = length(ray_C);
  vec3 dir_W = mat3(pc.T_W_C) * (ray_C / ray_scale);
  vec3 origin_W = pc.T_W_C[3].xyz;

  float t_hit;
  bool hit =
      marchRay(origin_W, dir_W, pc.min_depth_m * ray_scale, pc.max_depth_m * ray_scale, t_hit);
  uvec2 result = uvec2(0u);
  if (hit) {
    result.x = floatBitsToUint(t_hit / ray_scale);
    result.y = kHitBit;
    TsdfVoxel voxel;
    vec3 p_W = origin_W + dir_W * t_hit;
    if (readVoxel(ivec3(floor(p_W / pc.voxel_size_m)), voxel)) {
      result.y |= voxel.color_rgba & 0xFFFFFFu;
    }
  }
  uint i = g.y * pc.grid_size.x + g.x;
  float measured_m = measured_depth_m[i];
  // Only depths the map fuses count: beyond its range a surface can never be held.
  if (measured_m >= pc.min_depth_m && measured_m <= pc.max_depth_m && measured_m > 0.0) {
    result.y |= kMeasuredBit;
    float tsdf_m;
    if (sampleTsdf(origin_W + dir_W * (measured_m * ray_scale), tsdf_m) &&
        abs(tsdf_m) <= held_tolerance_m) {
      result.y |= kHeldBit;
    }
  }
  samples_out[i] = result;
}
