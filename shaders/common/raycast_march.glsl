// The ray march of raycast_tsdf (mirrored by raycastPixelReference on the host). Needs
// tsdf_sample.glsl. Steps: unallocated block -> jump to the block's exit; unobserved sample ->
// one voxel; observed sample -> max(one voxel, 0.8 * tsdf), which never jumps over the band
// behind a surface (the band is a full truncation distance thick and tsdf <= truncation).

// Distance along the ray from p to where it leaves the block containing p.
float blockExitDistance(vec3 p_W, vec3 dir_W) {
  float block_size_m = pc.voxel_size_m * float(kBlockEdge);
  vec3 lo = floor(p_W / block_size_m) * block_size_m;
  vec3 hi = lo + block_size_m;
  vec3 inv = 1.0 / max(abs(dir_W), vec3(1e-12));
  vec3 t = mix((lo - p_W) * -inv, (hi - p_W) * inv, greaterThan(dir_W, vec3(0.0)));
  return min(t.x, min(t.y, t.z));
}

bool marchRay(vec3 origin_W, vec3 dir_W, float t_min, float t_max, out float t_hit) {
  float t = t_min;
  float previous_t = 0.0;
  float previous_tsdf = 0.0;
  bool previous_valid = false;
  for (uint s = 0u; s < pc.max_steps && t <= t_max; ++s) {
    vec3 p_W = origin_W + dir_W * t;
    float tsdf_m;
    if (!sampleTsdf(p_W, tsdf_m)) {
      previous_valid = false;
      if (findBlockSlot(ivec3(floor(p_W / (pc.voxel_size_m * float(kBlockEdge))))) < 0) {
        t += blockExitDistance(p_W, dir_W) + 1e-4;
      } else {
        t += pc.voxel_size_m;
      }
      continue;
    }
    if (previous_valid && previous_tsdf > 0.0 && tsdf_m <= 0.0) {
      t_hit = previous_t + (t - previous_t) * previous_tsdf / (previous_tsdf - tsdf_m);
      return true;
    }
    previous_valid = true;
    previous_tsdf = tsdf_m;
    previous_t = t;
    t += max(pc.voxel_size_m, 0.8 * tsdf_m);
  }
  return false;
}

// Unit normal from central differences of the trilinear TSDF (points to free space);
// zero when a neighbour sample is unobserved.
vec3 surfaceNormal(vec3 p_W) {
  float h = pc.voxel_size_m;
  float s[6];
  for (int i = 0; i < 6; ++i) {
    vec3 offset = vec3(0.0);
    offset[i >> 1] = (i & 1) == 0 ? h : -h;
    if (!sampleTsdf(p_W + offset, s[i])) return vec3(0.0);
  }
  vec3 gradient = vec3(s[0] - s[1], s[2] - s[3], s[4] - s[5]);
  float len = length(gradient);
  return len > 0.0 ? gradient / len : vec3(0.0);
}
