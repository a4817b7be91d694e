#version 450
// smoke_add: out[i] = a[i] + b[i]. Used by the runtime tests only.
// Workgroup: 256 x 1 x 1. Bindings: 0 a (float[]), 1 b (float[]), 2 out (float[]).
// Push constants: uint count.
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer A { float a[]; };
layout(std430, binding = 1) readonly buffer B { float b[]; };
layout(std430, binding = 2) writeonly buffer Out { float result[]; };
layout(push_constant) uniform Push { uint count; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) result[i] = a[i] + b[i];
}
