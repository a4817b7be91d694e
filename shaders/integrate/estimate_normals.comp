#version 450
// estimate_normals: per-pixel surface normal of the depth image in the camera frame, from central
// differences of the back-projected neighbours, oriented toward the camera. Used by the
// point-to-plane signed distance of integrate_tsdf.
// Reference: engine/kernels/normal_estimation.cpp (estimateNormalsReference).
// Workgroup: 16 x 16 x 1, one invocation per pixel.
// Bindings: 0 float depth_m[], 1 vec4 normal_C[] (xyz unit normal, w = 1 valid / 0 invalid).
// Push constants: vec4 K, uvec2 image_size, float min_depth_m, max_depth_m, max_relative_jump.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Depth { float depth_m[]; };
layout(std430, binding = 1) writeonly buffer Normals { vec4 normal_C[]; };

layout(push_constant, std430) uniform Push {
  vec4 K;
  uvec2 image_size;
  float min_depth_m;
  float max_depth_m;
  float max_relative_jump;
  uint pad0;
  uint pad1;
  uint pad2;
} pc;

#include "normal_stencil.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.image_size))) return;
  normal_C[pixel.y * pc.image_size.x + pixel.x] = pixelNormal(ivec2(pixel));
}
