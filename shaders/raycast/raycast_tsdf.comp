#version 450
// raycast_tsdf: render the TSDF into a pinhole camera (depth, normal, colour, hit mask) by marching
// each pixel's ray with trilinear sampling and refining the first +/- zero crossing linearly.
// Reference: engine/kernels/raycast.cpp (raycastPixelReference is the same march).
// Workgroup: 16 x 16 x 1, one invocation per pixel.
// Bindings: 0 HashEntry entries[], 1 float depth_out_m[] (z, 0 = miss),
//           2 vec4 normal_out_W[] (xyz unit normal in world, w = 1 on hit), 3 uint color_out[].
// Push constants: RaycastPush (engine/kernels/device_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "camera.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Entries { HashEntry entries[]; };
layout(std430, binding = 1) writeonly buffer DepthOut { float depth_out_m[]; };
layout(std430, binding = 2) writeonly buffer NormalOut { vec4 normal_out_W[]; };
layout(std430, binding = 3) writeonly buffer ColorOut { uint color_out[]; };

layout(push_constant, std430) uniform Push {
  mat4 T_W_C;
  vec4 K;
  uvec2 image_size;
  float min_depth_m;
  float max_depth_m;
  float voxel_size_m;
  float truncation_m;
  uint hash_mask;
  float min_weight;
  uint64_t pool_address;
  uint max_steps;
  uint pad0;
} pc;

#include "tsdf_sample.glsl"
#include "raycast_march.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.image_size))) return;
  uint index = pixel.y * pc.image_size.x + pixel.x;

  vec3 ray_C = pixelRay(vec2(pixel), pc.K);
  float ray_scale = length(ray_C);
  vec3 dir_W = mat3(pc.T_W_C) * (ray_C / ray_scale);
  vec3 origin_W = pc.T_W_C[3].xyz;

  float t_hit;
  bool hit = marchRay(origin_W, dir_W, pc.min_depth_m * ray_scale, pc.max_depth_m * ray_scale, t_hit);
  depth_out_m[index] = hit ? t_hit / ray_scale : 0.0;
  vec4 normal = vec4(0.0);
  uint color = 0u;
  if (hit) {
    vec3 p_W = origin_W + dir_W * t_hit;
    normal = vec4(surfaceNormal(p_W), 1.0);
    TsdfVoxel voxel;
    if (readVoxel(ivec3(floor(p_W / pc.voxel_size_m)), voxel)) color = voxel.color_rgba;
  }
  normal_out_W[index] = normal;
  color_out[index] = color;
}
