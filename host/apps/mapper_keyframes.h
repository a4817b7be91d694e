#pragma once
// Keyframe scores for keyframe_score_t: each frame scored against the map as it was before the
// frame (raycast reprojection, select/keyframe_scorer.h), decided online by the selection's
// thresholds. NOTE: per frame, without the trajectory smoothing and dilation of offline
// selection (keyframe_selection.h), which need the frames after it.
// Thread safety: not thread safe.
#include <cstdint>

#include "kernels/device_tsdf_map.h"
#include "select/keyframe_scorer.h"
#include "select/keyframe_selection.h"
#include "strata/keyframe_score_t.hpp"

namespace strata::apps {

class MapperKeyframes {
 public:
  explicit MapperKeyframes(vk::Context& context,
                           const selection::Thresholds& thresholds = selection::Thresholds{});

  /// Scores `frame` against `map` (before the frame is fused into it).
  keyframe_score_t score(DeviceTsdfMap& map, const RgbdFrame& frame,
                         const CameraIntrinsics& intrinsics, std::int64_t frame_utime);

 private:
  selection::KeyframeScorer scorer_;
  selection::Thresholds thresholds_;
};

}  // namespace strata::apps
