#pragma once
// The prior map a robot localises against: the keyframes of a map store (store/session_store.h)
// with their map-frame poses, depth, ORB features, surface descriptions and the place index over
// them, as `strata align` builds and uses them (align/session_alignment.h). Loaded once, read by
// any number of Localizers.
// Map frame W: the store's world frame. A keyframe's pose is its optimised T_W_C where the store
// has one, else T_W_S * T_S_C of an aligned session; when nothing in the store is aligned (only
// `strata map import` ran), its first session anchors W (T_W_S = identity) and the others are
// left out. Metres, radians.
// Errors: InputError naming the session for a folder that is gone or changed since the import
// (as alignStore), a store without a usable session or keyframe. The store is only read.
// Thread safety: const after construction; several threads may read one PriorMap.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "strata/align/keyframe_features.h"
#include "strata/align/place_index.h"
#include "strata/align/surface_descriptor.h"
#include "strata/core/types.h"
#include "strata/store/session_store.h"

namespace strata::localize {

struct PriorMapConfig {
  align::FeatureConfig features;
  align::PlaceIndexConfig index;
  align::SurfaceConfig surface;
  /// Surface descriptions computed (the verifier's path for places without texture).
  bool surfaces = true;
  int threads = 2;  // loading workers
  void validate() const;
};

/// One keyframe of the prior map.
struct MapKeyframe {
  std::int64_t store_id = 0;    // keyframe id in the store (0: not from a store)
  std::int64_t session_id = 0;
  std::string session_name;
  double timestamp_s = 0.0;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  CameraIntrinsics intrinsics;
  DepthImage depth;
  align::KeyframeFeatures features;
  align::KeyframeSurface surface;  // empty when PriorMapConfig::surfaces is false
};

/// A frame as a map keyframe at pose frame.T_W_C: its depth, ORB features from its colour (none
/// without colour) and, with config.surfaces, its surface description. InputError for images
/// whose sizes disagree with the intrinsics.
MapKeyframe describeKeyframe(RgbdFrame frame, const CameraIntrinsics& intrinsics,
                             const PriorMapConfig& config);

/// done of total keyframes loaded.
using PriorMapProgress = std::function<void(std::size_t done, std::size_t total)>;

class PriorMap {
 public:
  /// From keyframes already in memory (their features and surfaces filled).
  PriorMap(std::vector<MapKeyframe> keyframes, const PriorMapConfig& config);

  /// Loads every usable session of `store` (see the header comment), reading each keyframe's
  /// images from the session's folder; stored features are lifted, missing ones extracted.
  static PriorMap fromStore(store::Store& store, const PriorMapConfig& config = {},
                            const PriorMapProgress& progress = {});

  const std::vector<MapKeyframe>& keyframes() const { return keyframes_; }
  const align::PlaceIndex& index() const { return index_; }
  const PriorMapConfig& config() const { return config_; }
  /// Names of the sessions the map holds and of those left out (unaligned), for reports.
  const std::vector<std::string>& sessions() const { return sessions_; }
  const std::vector<std::string>& skipped_sessions() const { return skipped_sessions_; }

 private:
  PriorMapConfig config_;
  std::vector<MapKeyframe> keyframes_;
  align::PlaceIndex index_;
  std::vector<std::string> sessions_, skipped_sessions_;
};

}  // namespace strata::localize
