#version 450
// track_normal_equations: point-to-plane ICP terms of one live level against a model raycast
// (projective association, distance and normal gates, Huber weight), reduced per workgroup.
// Reference: engine/track/normal_equations_reference.cpp (equations in normal_equations.h).
// Workgroup: 128 x 1 x 1 over a run of 128 * kPixelsPerInvocation pixels (row-major); each
// invocation sums the terms of its kPixelsPerInvocation pixels (stride 128), then one
// shared-memory tree reduction of the 29 sums per workgroup.
// Bindings: 0 vec4 live_vertex_C[], 1 vec4 live_normal_C[] (w = 1 valid), 2 float model_depth_m[]
//           (z, 0 = none), 3 vec4 model_normal_W[] (w = 1 on a hit), 4 TrackParams params,
//           5 float partials[] (32 per workgroup: JtJ upper triangle 21, Jtr 6, r^2, count).
// Push constants: uvec4 (live width, live height, model width, model height).
layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer LiveVertex { vec4 live_vertex_C[]; };
layout(std430, binding = 1) readonly buffer LiveNormal { vec4 live_normal_C[]; };
layout(std430, binding = 2) readonly buffer ModelDepth { float model_depth_m[]; };
layout(std430, binding = 3) readonly buffer ModelNormal { vec4 model_normal_W[]; };
layout(std430, binding = 4) readonly buffer Params {
  mat4 T_M_C;      // live camera -> model camera
  mat4 R_M_W;      // world -> model camera rotation (upper 3x3)
  vec4 K_model;    // fx, fy, cx, cy of the model image
  vec4 gates;      // max distance^2, min normal cos, huber (0 = off), unused
} params;
layout(std430, binding = 5) writeonly buffer Partials { float partials[]; };

layout(push_constant, std430) uniform Push { uvec4 sizes; } pc;

const uint kGroup = 128u;
const uint kTerms = 29u;
const uint kPixelsPerInvocation = 32u;
shared float sums[kTerms * kGroup];

// Fills t[] with the pixel's terms; false when it is not an inlier.
bool pixelTerms(uint index, out float t[kTerms]) {
  for (uint k = 0u; k < kTerms; ++k) t[k] = 0.0;
  if (index >= pc.sizes.x * pc.sizes.y) return false;
  vec4 p4 = live_vertex_C[index];
  vec4 n4 = live_normal_C[index];
  if (p4.w < 0.5 || n4.w < 0.5) return false;
  mat3 R_M_C = mat3(params.T_M_C);
  vec3 p_M = R_M_C * p4.xyz + params.T_M_C[3].xyz;
  if (!(p_M.z > 0.0)) return false;
  vec4 K = params.K_model;
  float u = K.x * p_M.x / p_M.z + K.z;
  float v = K.y * p_M.y / p_M.z + K.w;
  float fu = floor(u + 0.5);
  float fv = floor(v + 0.5);
  if (!(fu >= 0.0 && fv >= 0.0 && fu < float(pc.sizes.z) && fv < float(pc.sizes.w))) return false;
  uint model_index = uint(fv) * pc.sizes.z + uint(fu);
  float z_M = model_depth_m[model_index];
  vec4 nm4 = model_normal_W[model_index];
  if (nm4.w < 0.5 || !(z_M > 0.0)) return false;
  vec3 v_M = vec3((fu - K.z) / K.x, (fv - K.w) / K.y, 1.0) * z_M;
  vec3 n_M = mat3(params.R_M_W) * nm4.xyz;
  vec3 diff = p_M - v_M;
  if (dot(diff, diff) > params.gates.x) return false;
  if (dot(n_M, R_M_C * n4.xyz) < params.gates.y) return false;
  float r = dot(n_M, diff);
  vec3 n_C = transpose(R_M_C) * n_M;
  vec3 pxn = cross(p4.xyz, n_C);
  float J[6] = float[6](n_C.x, n_C.y, n_C.z, pxn.x, pxn.y, pxn.z);
  float huber = params.gates.z;
  float w = (huber > 0.0 && abs(r) > huber) ? huber / abs(r) : 1.0;
  uint k = 0u;
  for (uint i = 0u; i < 6u; ++i) {
    for (uint j = i; j < 6u; ++j) t[k++] = w * J[i] * J[j];
  }
  for (uint i = 0u; i < 6u; ++i) t[21u + i] = w * J[i] * r;
  t[27] = r * r;
  t[28] = 1.0;
  return true;
}

void main() {
  uint lid = gl_LocalInvocationIndex;
  float acc[kTerms];
  for (uint k = 0u; k < kTerms; ++k) acc[k] = 0.0;
  uint first = gl_WorkGroupID.x * kGroup * kPixelsPerInvocation + lid;
  for (uint i = 0u; i < kPixelsPerInvocation; ++i) {
    float t[kTerms];
    if (pixelTerms(first + i * kGroup, t)) {
      for (uint k = 0u; k < kTerms; ++k) acc[k] += t[k];
    }
  }
  for (uint k = 0u; k < kTerms; ++k) sums[k * kGroup + lid] = acc[k];
  barrier();
  for (uint stride = kGroup / 2u; stride > 0u; stride >>= 1u) {
    if (lid < stride) {
      for (uint k = 0u; k < kTerms; ++k) sums[k * kGroup + lid] += sums[k * kGroup + lid + stride];
    }
    barrier();
  }
  if (lid < kTerms) partials[gl_WorkGroupID.x * 32u + lid] = sums[lid * kGroup];
}
