#version 450
// stream_copy: dst[i] = src[i] over vec4s, the streaming ceiling strata-bench compares the
// integration kernel with (bench/streaming_ceiling.cpp). Benchmarks only.
// Workgroup: 256 x 1 x 1; dispatch (min(g, 65535), ceil(g / 65535)) groups for g = ceil(n / 256).
// Bindings: 0 vec4 src[], 1 vec4 dst[]. Push constants: uint count (vec4s).
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Src { vec4 src[]; };
layout(std430, binding = 1) writeonly buffer Dst { vec4 dst[]; };
layout(push_constant) uniform Push { uint count; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 256u;
  if (i < pc.count) dst[i] = src[i];
}
