// Per-voxel rules of change detection: mirror of engine/kernels/change_rules.h (the
// specification, with the reasons). Needs map_layout.glsl and change_layout.glsl first.

bool observed(TsdfVoxel v, float min_weight) { return v.weight >= min_weight; }

uint differenceLabel(TsdfVoxel s, TsdfVoxel m, float min_weight, float threshold_m) {
  if (!observed(s, min_weight) || !observed(m, min_weight)) return kLabelUnknown;
  return abs(m.tsdf_m - s.tsdf_m) > threshold_m ? kLabelDynamic : kLabelStatic;
}

uint sessionDynamicLabel(TsdfVoxel m, TsdfVoxel s, float min_weight, float threshold_m) {
  if (!observed(m, min_weight)) return kLabelUnknown;
  if (!observed(s, min_weight)) return kLabelDynamic;
  return m.tsdf_m < s.tsdf_m - threshold_m ? kLabelDynamic : kLabelStatic;
}

uint erodedLabel(uint raw, uint dynamic_in_cube, uint kernel_voxels) {
  if (raw != kLabelDynamic) return raw;
  return 2u * dynamic_in_cube >= kernel_voxels * kernel_voxels * kernel_voxels ? kLabelDynamic
                                                                               : kLabelStatic;
}

uint dilatedLabel(uint raw, uint eroded_dynamic_in_cube, uint mask) {
  if (raw == kLabelUnknown) return kLabelUnknown;
  bool allowed = mask == kMaskObserved || raw == kLabelDynamic;
  return allowed && eroded_dynamic_in_cube > 0u ? kLabelDynamic : kLabelStatic;
}

uint blendRgb(uint a, float weight_a, uint b, float weight_b) {
  vec3 ca = vec3(a & 255u, (a >> 8) & 255u, (a >> 16) & 255u);
  vec3 cb = vec3(b & 255u, (b >> 8) & 255u, (b >> 16) & 255u);
  vec3 c = (ca * weight_a + cb * weight_b) / (weight_a + weight_b);
  uvec3 q = uvec3(clamp(floor(c + 0.5), 0.0, 255.0));
  return q.x | (q.y << 8) | (q.z << 16);
}

TsdfVoxel mergeStatic(TsdfVoxel s, TsdfVoxel m, uint d, float min_weight, float merge_close_m,
                      float max_weight) {
  if (!observed(m, min_weight)) return s;
  if (!observed(s, min_weight)) return m;
  if (d == kLabelDynamic) {
    if (m.tsdf_m - s.tsdf_m > merge_close_m) return m;
    if (s.tsdf_m - m.tsdf_m > merge_close_m) return s;
  }
  float weight = s.weight + m.weight;
  TsdfVoxel merged;
  merged.tsdf_m = (s.tsdf_m * s.weight + m.tsdf_m * m.weight) / weight;
  merged.color_rgba = blendRgb(s.color_rgba, s.weight, m.color_rgba, m.weight);
  merged.weight = min(weight, max_weight);
  return merged;
}
