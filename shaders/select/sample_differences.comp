#version 450
// sample_differences: per raycast sample of keyframe selection, the colour and depth
// differences between the rendered map and the new keyframe, from which the host takes the
// upper-half means (keyframe_metrics.cpp). Colour: both images blurred with a 3x3 binomial over
// the grid, averaging only samples that hit the map (same support for both), then chromaticity
// 3 * rgb / max(r + g + b, 30) per sample, then the mean absolute channel difference. Depth:
// |new - rendered| beyond the tolerance, clipped.
// Reference: sampleDifferencesReference (engine/kernels/select_differences_reference.cpp); the
// blur sums in the same order so both round alike.
// Workgroup: 16 x 16 x 1, one invocation per sample.
// Bindings: 0 uvec2 samples[] (raycast_samples.comp's output), 1 uvec2 keyframe[] (x = new depth
//           in metres as float bits, 0 = none; y = colour r | g << 8 | b << 16), 2 vec2 out[]
//           (x = colour difference, y = depth difference; -1 where it does not apply).
// Push constants: SampleDifferencePush (engine/kernels/select_layout.h).
layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Samples { uvec2 samples[]; };
layout(std430, binding = 1) readonly buffer Keyframe { uvec2 keyframe[]; };
layout(std430, binding = 2) writeonly buffer Differences { vec2 differences[]; };

layout(push_constant, std430) uniform Push {
  uvec2 grid_size;
  float depth_tolerance_m;
  float max_depth_difference_m;
  uint has_color;
} pc;

const uint kHitBit = 0x80000000u;

bool hitAt(ivec2 g) { return (samples[g.y * int(pc.grid_size.x) + g.x].y & kHitBit) != 0u; }

vec3 unpackRgb(uint word) {
  return vec3(float(word & 255u), float((word >> 8) & 255u), float((word >> 16) & 255u));
}

vec3 chromaticity(vec3 rgb) { return rgb * (3.0 / max(rgb.r + rgb.g + rgb.b, 30.0)); }

void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(pc.grid_size);
  if (any(greaterThanEqual(g, size))) return;
  uint i = uint(g.y * size.x + g.x);
  vec2 result = vec2(-1.0);
  if (hitAt(g)) {
    float new_depth_m = uintBitsToFloat(keyframe[i].x);
    if (new_depth_m > 0.0) {
      float beyond = abs(new_depth_m - uintBitsToFloat(samples[i].x)) - pc.depth_tolerance_m;
      result.y = clamp(beyond, 0.0, pc.max_depth_difference_m);
    }
    if (pc.has_color != 0u) {
      vec3 rendered = vec3(0.0), observed = vec3(0.0);
      float weight = 0.0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          ivec2 n = g + ivec2(dx, dy);
          if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size)) || !hitAt(n)) continue;
          float w = float(2 - abs(dx)) * float(2 - abs(dy));
          uint k = uint(n.y * size.x + n.x);
          rendered += w * unpackRgb(samples[k].y);
          observed += w * unpackRgb(keyframe[k].y);
          weight += w;
        }
      }
      vec3 d = abs(chromaticity(rendered / weight) - chromaticity(observed / weight));
      result.x = (d.r + d.g + d.b) / 3.0;
    }
  }
  differences[i] = result;
}
