#pragma once
// The per-voxel rules of change detection (docs/change.md, steps 2-5): the specification
// that the reference passes (change_reference.h) apply on the host and
// shaders/common/change_rules.glsl mirrors on the device. A voxel of a layer is observed when its
// weight is at least ChangeConfig::min_weight.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "strata/change/change_config.h"
#include "strata/change/change_labels.h"
#include "strata/map/tsdf_map.h"

namespace strata::change {

inline bool observed(const TsdfVoxel& v, const ChangeConfig& config) {
  return v.weight >= config.min_weight;
}

/// Step 2, differencing S against the new session M_N (change_difference.comp): kUnknown unless
/// both are observed; kDynamic where |f_M - f_S| > theta; kStatic otherwise.
inline VoxelLabel differenceLabel(const TsdfVoxel& s, const TsdfVoxel& m,
                                  const ChangeConfig& config) {
  if (!observed(s, config) || !observed(m, config)) return VoxelLabel::kUnknown;
  return std::fabs(m.tsdf_m - s.tsdf_m) > config.difference_threshold_m ? VoxelLabel::kDynamic
                                                                        : VoxelLabel::kStatic;
}

/// Step 5 before clean-up, session i against S (change_session_dynamic.comp): kUnknown unless M_i
/// is observed; kDynamic where S is unobserved or f_M < f_S - theta (something stood there in
/// session i that S does not have: adding an object only lowers the distance); kStatic otherwise.
/// NOTE: once M_i is merged into S, S is observed wherever M_i is (mergeStatic), so through
/// ChangeDetector only the "clearly below" part can fire.
inline VoxelLabel sessionDynamicLabel(const TsdfVoxel& m, const TsdfVoxel& s,
                                      const ChangeConfig& config) {
  if (!observed(m, config)) return VoxelLabel::kUnknown;
  if (!observed(s, config)) return VoxelLabel::kDynamic;
  return m.tsdf_m < s.tsdf_m - config.difference_threshold_m ? VoxelLabel::kDynamic
                                                             : VoxelLabel::kStatic;
}

/// Step 3, erosion (change_erode.comp): a dynamic voxel stays dynamic when at least half of the
/// kernel^3 cube centred on it (itself included) is dynamic; voxels of unallocated blocks count as
/// not dynamic. A dynamic voxel that fails becomes kStatic; other labels are kept.
inline VoxelLabel erodedLabel(VoxelLabel raw, int dynamic_in_cube, int kernel_voxels) {
  if (raw != VoxelLabel::kDynamic) return raw;
  return 2 * dynamic_in_cube >= kernel_voxels * kernel_voxels * kernel_voxels ? VoxelLabel::kDynamic
                                                                              : VoxelLabel::kStatic;
}

/// Where dilation may place a dynamic label.
enum class DilationMask : std::uint32_t {
  kObserved = 0,    // D: voxels observed in both layers (raw label not kUnknown)
  kRawDynamic = 1,  // a session's dynamic part: only its raw dynamic voxels (so it stays a
                    // subset of them; the dilation then only restores what erosion removed)
};

/// Step 3, dilation (change_dilate.comp): kDynamic where the mask allows and the kernel^3 cube
/// centred on the voxel holds an eroded dynamic voxel; otherwise kUnknown where the raw label is,
/// kStatic elsewhere.
inline VoxelLabel dilatedLabel(VoxelLabel raw, int eroded_dynamic_in_cube, DilationMask mask) {
  if (raw == VoxelLabel::kUnknown) return VoxelLabel::kUnknown;
  const bool allowed = mask == DilationMask::kObserved || raw == VoxelLabel::kDynamic;
  return allowed && eroded_dynamic_in_cube > 0 ? VoxelLabel::kDynamic : VoxelLabel::kStatic;
}

/// Weighted average of colour channels (r | g << 8 | b << 16), rounded like the integration.
inline std::uint32_t blendRgb(std::uint32_t a, float weight_a, std::uint32_t b, float weight_b) {
  std::uint32_t out = 0;
  for (int channel = 0; channel < 3; ++channel) {
    const float ca = static_cast<float>((a >> (8 * channel)) & 255u);
    const float cb = static_cast<float>((b >> (8 * channel)) & 255u);
    const float c = (ca * weight_a + cb * weight_b) / (weight_a + weight_b);
    out |= static_cast<std::uint32_t>(std::clamp(std::floor(c + 0.5f), 0.0f, 255.0f))
           << (8 * channel);
  }
  return out;
}

/// Step 4, static update of S with M_N (change_static_update.comp), `d` the voxel's label in D:
/// - M unobserved: S unchanged (an unobserved value never overwrites an observed one, and S only
///   ever holds observed values, so S starts as the first session's observed voxels);
/// - S unobserved: S takes M (value, weight, colour): space seen for the first time, such as
///   floor uncovered by a removed object;
/// - both observed, d dynamic and f_M > f_S + merge_close: S takes M (removing an object can only
///   increase the distance); f_M < f_S - merge_close: S unchanged (an added object stays out);
/// - otherwise (static, or dynamic but close): the ordinary weighted average, weight clamped at
///   max_weight.
inline TsdfVoxel mergeStatic(const TsdfVoxel& s, const TsdfVoxel& m, VoxelLabel d,
                             const ChangeConfig& config, float max_weight) {
  if (!observed(m, config)) return s;
  if (!observed(s, config)) return m;
  if (d == VoxelLabel::kDynamic) {
    if (m.tsdf_m - s.tsdf_m > config.merge_close_m) return m;
    if (s.tsdf_m - m.tsdf_m > config.merge_close_m) return s;
  }
  const float weight = s.weight + m.weight;
  TsdfVoxel out;
  out.tsdf_m = (s.tsdf_m * s.weight + m.tsdf_m * m.weight) / weight;
  out.color_rgba = blendRgb(s.color_rgba, s.weight, m.color_rgba, m.weight);
  out.weight = std::min(weight, max_weight);
  return out;
}

}  // namespace strata::change
