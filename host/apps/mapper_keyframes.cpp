#include "apps/mapper_keyframes.h"

#include <string>

#include "lcm/lcm_time.h"

namespace strata::apps {

MapperKeyframes::MapperKeyframes(vk::Context& context, const selection::Thresholds& thresholds)
    : scorer_(context), thresholds_(thresholds) {}

keyframe_score_t MapperKeyframes::score(DeviceTsdfMap& map, const RgbdFrame& frame,
                                        const CameraIntrinsics& intrinsics,
                                        std::int64_t frame_utime) {
  const selection::KeyframeScore s = scorer_.score(map, frame, intrinsics);
  keyframe_score_t out{};
  out.utime = lcm_io::nowUtime();
  out.frame_utime = frame_utime;
  out.coverage = static_cast<float>(s.coverage);
  out.change = static_cast<float>(s.color_change);
  const auto used = [](double threshold) { return threshold >= 0.0; };  // < 0: not used
  std::string reason;
  if (used(thresholds_.coverage) && s.coverage < thresholds_.coverage) {
    reason = "coverage " + std::to_string(s.coverage) + " below " +
             std::to_string(thresholds_.coverage) + " (new space)";
  } else if (used(thresholds_.color_change) && s.color_change > thresholds_.color_change) {
    reason = "colour change " + std::to_string(s.color_change) + " above " +
             std::to_string(thresholds_.color_change);
  } else if (used(thresholds_.depth_change_m) && s.depth_change_m > thresholds_.depth_change_m) {
    reason = "depth change " + std::to_string(s.depth_change_m) + " m above " +
             std::to_string(thresholds_.depth_change_m) + " m";
  } else if (used(thresholds_.surface_change) && s.surface_change > thresholds_.surface_change) {
    reason = "surface change " + std::to_string(s.surface_change) + " above " +
             std::to_string(thresholds_.surface_change) + " (measured surface the map lacks)";
  }
  out.selected = !reason.empty();
  out.reason = out.selected ? reason : "map already explains the frame";
  return out;
}

}  // namespace strata::apps
