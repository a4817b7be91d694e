#include "mapper_node/mapper_core.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>

#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/lcm/block_mesh_msg.h"
#include "strata/lcm/convert_change.h"
#include "strata/lcm/convert_objects.h"
#include "strata/lcm/esdf_slice_msg.h"
#include "strata/lcm/lcm_time.h"
#include "strata/objects/object_database.h"
#include "strata/objects/object_database_file.h"

namespace strata::apps {
namespace {

MeshOptions blockMeshOptions() {
  MeshOptions options;
  options.compute_normals = false;  // mesh_block_t carries positions and colours only
  return options;
}

const MapperOptions& validated(const MapperOptions& options) {
  options.validate();
  return options;
}

}  // namespace

MapperConfig mapperConfig(const MapperOptions& options) {
  MapperConfig config;
  config.map = options.map;
  if (options.change_detection) {
    // The session layers change detection compares: constant weights (change_min_weight counts
    // the frames that saw a voxel) and observed free space, at the mapper's voxel size and range.
    MapConfig change_map = change::changeMapConfig(options.map.voxel_size_m);
    change_map.max_depth_m = options.map.max_depth_m;
    change_map.min_depth_m = options.map.min_depth_m;
    change_map.truncation_voxels = options.map.truncation_voxels;
    change_map.max_block_capacity = options.map.max_block_capacity;
    config.map = change_map;
    config.change_detection = true;
    config.release_ended_sessions = true;  // a live mapper runs session after session
    config.keep_session_evidence = options.object_database;
    config.change.min_weight = options.change_min_weight;
    config.change.difference_threshold_m =
        options.change_threshold_voxels * options.map.voxel_size_m;
    config.change.merge_close_m = options.map.voxel_size_m;
  }
  config.esdf = options.esdf_rate_hz > 0.0;
  config.keyframe_scoring = options.keyframe_scores;
  return config;
}

MapperCore::MapperCore(vk::Context& context, const MapperOptions& options,
                       const MapFileContents* start)
    : context_(context),
      options_(validated(options)),
      mapper_(start ? Mapper::resume(*start, context, mapperConfig(options_))
                    : std::make_unique<Mapper>(mapperConfig(options_), context)) {
  if (mapper_->sessionOpen()) session_ = mapper_->sessionCount() - 1;
  if (!options_.change_detection || !options_.object_database) return;
  const std::string path = options_.objectsFile();
  std::error_code error;
  if (!path.empty() && std::filesystem::exists(path, error)) {
    try {
      objects_ = std::make_unique<objects::ObjectDatabase>(objects::loadObjectDatabase(path));
    } catch (const InputError& e) {
      throw InputError(std::string("cannot resume the object database (left untouched; move it "
                                   "away to start an empty one): ") +
                       e.what());
    }
    for (const int s : objects_->sessions())
      next_object_session_ = std::max(next_object_session_, s + 1);
  } else {
    objects_ = std::make_unique<objects::ObjectDatabase>();
  }
}

MapperCore::~MapperCore() {
  if (object_job_.valid()) object_job_.wait();  // it works on objects_
}

bool MapperCore::fuse(const lcm_io::ReadyFrame& ready, keyframe_score_t* score) {
  const auto start = std::chrono::steady_clock::now();
  const bool scored = options_.keyframe_scores && score != nullptr;
  // Before fusing: the score says what the frame adds to the map as it was.
  if (scored) {
    const KeyframeDecision decision = mapper_->scoreKeyframe(ready.frame, ready.intrinsics);
    *score = keyframe_score_t{};
    score->utime = lcm_io::nowUtime();
    score->frame_utime = ready.utime;
    score->coverage = static_cast<float>(decision.score.coverage);
    score->change = static_cast<float>(decision.score.color_change);
    score->selected = decision.keyframe;
    score->reason = decision.reason;
  }
  if (!mapper_->sessionOpen()) session_ = mapper_->beginSession();
  mapper_->integrate(ready.frame, ready.intrinsics);
  ++frames_fused_;
  last_frame_utime_ = ready.utime;
  last_fuse_ms_ =
      msSince(start);
  total_fuse_ms_ += last_fuse_ms_;
  return scored;
}

bool MapperCore::meshUpdate(bool full, std::int64_t utime, mesh_update_t* update) {
  if (full) mapper_->resetMeshStream();
  const std::vector<BlockMesh> blocks = mapper_->meshChangedBlocks(blockMeshOptions());
  if (!full && blocks.empty()) return false;
  *update = mesh_update_t{};
  update->utime = utime;
  update->last_frame_utime = last_frame_utime_;
  update->sequence = mesh_sequence_++;
  update->full = full;
  update->voxel_size_m = mapper_->config().map.voxel_size_m;
  for (const BlockMesh& block : blocks) update->blocks.push_back(lcm_io::toMessage(block));
  update->num_blocks = static_cast<std::int32_t>(update->blocks.size());
  return true;
}

bool MapperCore::esdfSlice(std::int64_t utime, esdf_slice_t* slice) {
  if (!mapper_->config().esdf || frames_fused_ == 0) return false;
  mapper_->updateEsdf();
  *slice = lcm_io::makeEsdfSlice(mapper_->esdf(), options_.esdf_slice_z_m, utime);
  slice->last_frame_utime = last_frame_utime_;
  return true;
}

std::vector<change_event_t> MapperCore::startSession(std::int64_t utime) {
  std::vector<change_event_t> events;
  if (mapper_->sessionOpen()) events = endSession(utime);
  session_ = mapper_->beginSession();
  return events;
}

std::vector<change_event_t> MapperCore::stopSession(std::int64_t utime) {
  if (!mapper_->sessionOpen()) throw InputError("no session is open");
  return endSession(utime);
}

std::vector<change_event_t> MapperCore::endSession(std::int64_t utime) {
  SessionResult result = mapper_->endSession();
  std::vector<change_event_t> events;
  if (!mapper_->config().change_detection) return events;
  for (const change::DiscoveredObject& object : result.objects) {
    events.push_back(
        lcm_io::encodeChangeEvent(object, static_cast<int>(result.objects.size()), utime));
  }
  if (objects_) addToObjectDatabase(std::move(result), utime);
  return events;
}

void MapperCore::addToObjectDatabase(SessionResult result, std::int64_t utime) {
  finishObjectJob();                // sessions enter the database in order, one at a time
  if (!result.session_map) return;  // no evidence kept: nothing to build models from
  const int session = next_object_session_++;
  // NOTE: the evidence (the session's map and surface) moves to the database thread, which alone
  // touches objects_ until it is done; the mapper keeps fusing on this thread.
  auto evidence = std::make_shared<SessionResult>(std::move(result));
  object_job_ = std::async(std::launch::async, [this, evidence, session, utime] {
    return objectUpdatesOf(*evidence, session, utime);
  });
}

std::vector<object_update_t> MapperCore::objectUpdatesOf(const SessionResult& result, int session,
                                                         std::int64_t utime) {
  const std::vector<objects::SegmentOutcome> outcomes =
      objects_->addSession(session, *result.session_map, result.surface, result.objects);
  std::map<int, bool> touched;  // model id -> founded by this session
  for (const objects::SegmentOutcome& o : outcomes) {
    if (o.model_id > 0) touched[o.model_id] = touched[o.model_id] || o.new_model;
    for (const int joined : o.joined_models) touched[joined] = false;
  }
  // A model joined into another (retired) goes out as its id with no instances and no mesh.
  std::vector<object_update_t> updates;
  const int count = static_cast<int>(touched.size());
  for (const auto& [id, founded] : touched) {
    const objects::ObjectModel* model = objects_->findModel(id);
    objects::ObjectModel retired;
    retired.id = id;
    updates.push_back(lcm_io::encodeObjectUpdate(
        model != nullptr ? *model : retired, session, founded && model != nullptr,
        static_cast<int>(updates.size()) + 1, count, utime));
  }
  return updates;
}

void MapperCore::finishObjectJob() {
  if (!object_job_.valid()) return;
  try {
    std::vector<object_update_t> updates = object_job_.get();
    object_updates_.insert(object_updates_.end(), updates.begin(), updates.end());
  } catch (...) {
    object_error_ = std::current_exception();
  }
}

bool MapperCore::objectUpdatesReady() const {
  if (object_job_.valid()) {
    return object_job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  }
  return !object_updates_.empty() || object_error_ != nullptr;
}

std::vector<object_update_t> MapperCore::takeObjectUpdates(bool wait) {
  if (object_job_.valid() &&
      (wait || object_job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready)) {
    finishObjectJob();
  }
  if (object_error_) {
    std::exception_ptr error = object_error_;
    object_error_ = nullptr;
    std::rethrow_exception(error);
  }
  std::vector<object_update_t> updates;
  updates.swap(object_updates_);
  return updates;
}

bool MapperCore::saveObjects() {
  finishObjectJob();
  const std::string path = options_.objectsFile();
  if (!objects_ || path.empty()) return false;
  objects::saveObjectDatabase(*objects_, path);
  return true;
}

const objects::ObjectDatabase* MapperCore::objectDatabase() {
  finishObjectJob();
  return objects_.get();
}

TsdfMap MapperCore::downloadMap() { return mapper_->download(); }

void MapperCore::saveMap(const std::string& path) {
  if (path.empty()) throw InputError("no map path: pass one with the command or --map");
  mapper_->save(path);
}

}  // namespace strata::apps
