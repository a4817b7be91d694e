// Pinhole camera helpers shared by the kernels; mirrored by engine/kernels/camera_math.h.
// Intrinsics packed as vec4(fx, fy, cx, cy); pixel centres at integer coordinates.

// Unnormalised ray direction through pixel (u, v) in the camera frame, z = 1.
vec3 pixelRay(vec2 uv, vec4 K) { return vec3((uv.x - K.z) / K.x, (uv.y - K.w) / K.y, 1.0); }

// A depth sample is used when it lies in [min_depth, max_depth]; NaN fails both comparisons.
bool depthValid(float depth_m, float min_depth_m, float max_depth_m) {
  return depth_m >= min_depth_m && depth_m <= max_depth_m;
}
