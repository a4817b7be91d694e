// Normal of the depth surface at a pixel (mirrored by estimateNormalsReference). Needs a
// `depth_m[]` binding and `pc` with K, image_size, min/max_depth_m and max_relative_jump.
// Invalid (w = 0) at the image border, next to invalid depth, and across depth discontinuities
// (a neighbour differing by more than max_relative_jump * depth): there the integration falls back
// to the distance along the ray.

float depthAt(ivec2 p) { return depth_m[uint(p.y) * pc.image_size.x + uint(p.x)]; }

vec4 pixelNormal(ivec2 p) {
  if (p.x < 1 || p.y < 1 || p.x + 1 >= int(pc.image_size.x) || p.y + 1 >= int(pc.image_size.y)) {
    return vec4(0.0);
  }
  float d = depthAt(p);
  float d_left = depthAt(p + ivec2(-1, 0));
  float d_right = depthAt(p + ivec2(1, 0));
  float d_up = depthAt(p + ivec2(0, -1));
  float d_down = depthAt(p + ivec2(0, 1));
  if (!depthValid(d, pc.min_depth_m, pc.max_depth_m) ||
      !depthValid(d_left, pc.min_depth_m, pc.max_depth_m) ||
      !depthValid(d_right, pc.min_depth_m, pc.max_depth_m) ||
      !depthValid(d_up, pc.min_depth_m, pc.max_depth_m) ||
      !depthValid(d_down, pc.min_depth_m, pc.max_depth_m)) {
    return vec4(0.0);
  }
  float max_jump = pc.max_relative_jump * d;
  if (abs(d_left - d) > max_jump || abs(d_right - d) > max_jump || abs(d_up - d) > max_jump ||
      abs(d_down - d) > max_jump) {
    return vec4(0.0);
  }
  vec3 left = pixelRay(vec2(p + ivec2(-1, 0)), pc.K) * d_left;
  vec3 right = pixelRay(vec2(p + ivec2(1, 0)), pc.K) * d_right;
  vec3 up = pixelRay(vec2(p + ivec2(0, -1)), pc.K) * d_up;
  vec3 down = pixelRay(vec2(p + ivec2(0, 1)), pc.K) * d_down;
  vec3 n = cross(right - left, down - up);
  float len = length(n);
  if (!(len > 0.0)) return vec4(0.0);
  n /= len;
  // Toward the camera: the surface point's ray and the normal must point against each other.
  if (dot(n, pixelRay(vec2(p), pc.K)) > 0.0) n = -n;
  return vec4(n, 1.0);
}
