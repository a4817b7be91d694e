#pragma once
// Change detection over whole sessions (what `strata diff`, `strata demo` and `strata objects`
// run): sessions fused by a Mapper with change detection one after the other, then the static
// mesh and every session's discovered objects against the final static map.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "strata/core/progress.h"
#include "strata/change/change_detector.h"
#include "strata/mapper/mapper.h"
#include "strata/change/object_discovery.h"
#include "strata/core/dataset.h"
#include "strata/mesh/mesh.h"

namespace strata {

struct DiffSession {
  std::string source;                // folder, map file or simulated session name
  std::size_t frames = 0;            // 0 for a saved map
  double load_s = 0.0;               // reading (or rendering) the frames
  double fuse_wall_ms = 0.0;         // summed over frames
  double fuse_device_ms = 0.0;       // summed over frames
  change::ChangeUpdateStats update;  // endSession of this session
  change::LabelledSurface surface;   // its mesh and refined face labels
  std::vector<change::DiscoveredObject> objects;
  change::ObjectStats object_stats;
};

struct DiffResult {
  Mesh static_mesh;
  std::vector<DiffSession> sessions;
  double objects_s = 0.0;  // meshing + object discovery, all sessions
};

/// Thread safety: not thread safe.
class DiffPipeline {
 public:
  /// Device mode on `context` (which must outlive the pipeline). Validates the configs.
  DiffPipeline(vk::Context& context, const MapConfig& map_config,
               const change::ChangeConfig& change_config, const change::ObjectConfig& objects);

  /// Runs on a session after its frames are fused, before it ends (to edit its layer).
  using BeforeEnd = std::function<void(change::ChangeDetector&, int session)>;
  /// Fuses every frame of `dataset` into a new session and ends it. `progress` counts frames
  /// (`done` carries the count across sessions).
  void addSession(const Dataset& dataset, const std::string& source, ProgressBar& progress,
                  std::size_t& done, const BeforeEnd& before_end = {});
  /// Adds a saved map as the next session and ends it.
  void addSessionMap(const TsdfMap& map, const std::string& source);
  /// Static mesh and every session's objects against the final static map. `maps` (optional)
  /// receives every session's own map (host copies). Call once, after the last session.
  DiffResult finish(std::vector<TsdfMap>* maps = nullptr);

  change::ChangeDetector& detector() { return mapper_.changeDetector(); }

 private:
  Mapper mapper_;
  change::ObjectConfig object_config_;
  std::vector<DiffSession> sessions_;
};

}  // namespace strata
