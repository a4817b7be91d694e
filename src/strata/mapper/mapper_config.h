#pragma once
// The one configuration of a Mapper: the map, and which capabilities run beside fusion.
// validate() is called by the Mapper's constructor and throws InputError naming the field.
#include <string>

#include "strata/change/change_config.h"
#include "strata/change/object_discovery.h"
#include "strata/map/esdf_layer.h"
#include "strata/map/map_config.h"
#include "strata/select/keyframe_scorer.h"
#include "strata/select/keyframe_selection.h"
#include "strata/track/track_config.h"

namespace strata {

struct MapperConfig {
  /// Voxel size, truncation, weights, depth range, capacities (map/map_config.h). With change
  /// detection on it is the map of every session layer and of the static estimate.
  MapConfig map;

  /// Keep an ESDF beside the TSDF: updateEsdf() and the distance / collision queries. Planners
  /// want map.allocate_free_space too (the ESDF covers only allocated blocks).
  bool esdf = false;
  /// Range, site threshold, minimum weight of the ESDF (map/esdf_layer.h).
  EsdfConfig esdf_config;

  /// Multi-session change detection: each session is fused into a TSDF layer of its own that
  /// shares the block index with the static estimate S; endSession() merges it into S and
  /// discovers the objects that moved. Off: one TSDF layer, sessions only count.
  bool change_detection = false;
  /// Difference threshold, erosion, dilation, minimum weight (change/change_config.h).
  change::ChangeConfig change;
  /// How a session's dynamic voxels become objects (change/object_discovery.h).
  change::ObjectConfig objects;
  /// endSession() discovers the session's objects against the static estimate as it ends. Off:
  /// SessionResult::objects stays empty, for programs that discover them later against the
  /// final static estimate (strata diff).
  bool discover_objects = true;
  /// endSession() frees the ended session's layers (change/change_detector.h releaseSession)
  /// after its objects are found: the next session reuses them, so a mapper that runs for days
  /// keeps its device memory bounded. Off: every session keeps a TSDF and a label layer for
  /// later questions about it (strata diff asks against the final static estimate).
  bool release_ended_sessions = false;
  /// With discover_objects: endSession() and addSessionMap() also return the session's own map
  /// (host copy) and its labelled surface (SessionResult::session_map, surface), what the
  /// object database needs to turn each discovered object into a model. Costs a download of the
  /// session layer, which object discovery makes anyway.
  bool keep_session_evidence = false;

  /// scoreKeyframe(): raycast-reprojection metrics of a frame against the map before it.
  bool keyframe_scoring = false;
  /// Sample grid, tolerances (select/keyframe_scorer.h).
  selection::ScorerConfig scorer;
  /// The decision of scoreKeyframe(): a frame is a keyframe when a metric passes its threshold.
  selection::Thresholds keyframe_thresholds;

  /// Tracking of frames without poses (Mapper::track, trackAndIntegrate): pyramid, gates,
  /// failure rules (track/track_config.h). Used only when those are called.
  TrackConfig track;

  /// Throws InputError naming the bad field (of this struct or of a nested config).
  void validate() const;
  /// One line for summaries: voxel size, truncation, and the capabilities on.
  std::string describe() const;
};

}  // namespace strata
