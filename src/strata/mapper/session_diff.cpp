#include "strata/mapper/session_diff.h"

#include <chrono>

#include "strata/core/clock.h"
#include "strata/mesh/extract_mesh.h"

namespace strata {
namespace {

using Clock = std::chrono::steady_clock;

/// Objects are discovered once, in finish(), against the final static map.
MapperConfig diffMapperConfig(const MapConfig& map_config, const change::ChangeConfig& change,
                              const change::ObjectConfig& objects) {
  MapperConfig c;
  c.map = map_config;
  c.change_detection = true;
  c.change = change;
  c.objects = objects;
  c.discover_objects = false;
  return c;
}

}  // namespace

DiffPipeline::DiffPipeline(vk::Context& context, const MapConfig& map_config,
                           const change::ChangeConfig& change_config,
                           const change::ObjectConfig& objects)
    : mapper_(diffMapperConfig(map_config, change_config, objects), context),
      object_config_(objects) {}

void DiffPipeline::addSession(const Dataset& dataset, const std::string& source,
                              ProgressBar& progress, std::size_t& done,
                              const BeforeEnd& before_end) {
  DiffSession session;
  session.source = source;
  session.frames = dataset.size();
  const int index = mapper_.beginSession();
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const auto load_start = Clock::now();
    const RgbdFrame frame = dataset.load(i);
    session.load_s += msSince(load_start) / 1000.0;
    const FrameStats stats = mapper_.integrate(frame, dataset.intrinsics()).fusion;
    session.fuse_wall_ms += stats.wall_ms;
    session.fuse_device_ms +=
        stats.upload_ms + stats.normals_ms + stats.allocate_ms + stats.integrate_ms;
    progress.update(++done);
  }
  if (before_end) before_end(mapper_.changeDetector(), index);
  session.update = mapper_.endSession().update;
  sessions_.push_back(std::move(session));
}

void DiffPipeline::addSessionMap(const TsdfMap& map, const std::string& source) {
  DiffSession session;
  session.source = source;
  session.update = mapper_.addSessionMap(map).update;
  sessions_.push_back(std::move(session));
}

DiffResult DiffPipeline::finish(std::vector<TsdfMap>* maps) {
  const auto start = Clock::now();
  DiffResult result;
  MeshOptions mesh_options;
  // The static map's own observation threshold: below it S holds no trusted value.
  change::ChangeDetector& detector = mapper_.changeDetector();
  mesh_options.min_weight = detector.config().min_weight;
  result.static_mesh = extractMesh(detector.staticMap(), mesh_options);
  for (std::size_t i = 0; i < sessions_.size(); ++i) {
    const int index = static_cast<int>(i);
    TsdfMap map = detector.sessionMap(index);
    DiffSession& s = sessions_[i];
    s.objects = change::extractObjects(map, detector.sessionDynamic(index), object_config_, index,
                                       &s.object_stats, &s.surface);
    if (maps != nullptr) maps->push_back(std::move(map));
  }
  result.sessions = std::move(sessions_);
  sessions_.clear();
  result.objects_s = msSince(start) / 1000.0;
  return result;
}

}  // namespace strata
