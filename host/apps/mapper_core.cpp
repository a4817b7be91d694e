#include "apps/mapper_core.h"

#include <chrono>

#include "apps/diff_pipeline.h"
#include "apps/mapper_keyframes.h"
#include "change/change_detector.h"
#include "change/objects.h"
#include "core/error.h"
#include "lcm/block_mesh.h"
#include "lcm/convert_change.h"
#include "lcm/esdf_slice_msg.h"
#include "map/map_file.h"

namespace strata::apps {
namespace {

MeshOptions blockMeshOptions() {
  MeshOptions options;
  options.compute_normals = false;  // mesh_block_t carries positions and colours only
  return options;
}

}  // namespace

MapperCore::MapperCore(vk::Context& context, const MapperOptions& options)
    : options_(options), context_(context), host_map_(options.map) {
  options_.validate();
  fusion_ = std::make_unique<DeviceFusion>(context_, options_.map);
  // Touched blocks drive both the mesh updates and the incremental ESDF.
  fusion_->setTrackTouchedBlocks(true);
  if (options_.keyframe_scores) keyframes_ = std::make_unique<MapperKeyframes>(context_);
  if (options_.esdf_rate_hz > 0.0) esdf_ = std::make_unique<DeviceEsdf>(context_, fusion_->map());
  if (options_.change_detection) {
    MapConfig change_map = changeMapConfig(options_.map.voxel_size_m);
    change_map.max_depth_m = options_.map.max_depth_m;
    // Constant weights: change_min_weight then counts the frames that saw a voxel (as strata demo).
    change_map.weight_mode = WeightMode::kConstant;
    change::ChangeConfig change_config;
    change_config.min_weight = options_.change_min_weight;
    change_config.difference_threshold_m =
        options_.change_threshold_voxels * options_.map.voxel_size_m;
    change_config.merge_close_m = options_.map.voxel_size_m;
    detector_ = std::make_unique<change::ChangeDetector>(context_, change_map, change_config);
  }
}

MapperCore::~MapperCore() = default;

void MapperCore::openSessionIfNeeded() {
  if (session_active_) return;
  session_ = detector_ ? detector_->beginSession() : session_ + 1;
  session_active_ = true;
}

bool MapperCore::fuse(const lcm_io::ReadyFrame& ready, keyframe_score_t* score) {
  const auto start = std::chrono::steady_clock::now();
  const bool scored = keyframes_ && score != nullptr;
  // Before fusing: the score says what the frame adds to the map as it was.
  if (scored)
    *score = keyframes_->score(fusion_->map(), ready.frame, ready.intrinsics, ready.utime);
  openSessionIfNeeded();
  fusion_->integrate(ready.frame, ready.intrinsics);
  const std::vector<BlockIndex>& touched = fusion_->lastTouchedBlocks();
  dirty_blocks_.insert(touched.begin(), touched.end());
  if (esdf_) esdf_->markDirty(touched);
  if (detector_) detector_->integrate(session_, ready.frame, ready.intrinsics);
  ++frames_fused_;
  last_frame_utime_ = ready.utime;
  last_fuse_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  total_fuse_ms_ += last_fuse_ms_;
  return scored;
}

bool MapperCore::meshUpdate(bool full, std::int64_t utime, mesh_update_t* update) {
  if (!full && dirty_blocks_.empty()) return false;
  // Only the blocks fused since the last update changed on the device.
  const std::vector<BlockIndex> dirty(dirty_blocks_.begin(), dirty_blocks_.end());
  if (full) {
    fusion_->map().download(host_map_);
  } else {
    fusion_->map().downloadBlocks(dirty, host_map_);
  }
  const std::vector<BlockIndex> blocks =
      full ? host_map_.sortedBlockIndices()
           : lcm_io::blocksToRemesh(host_map_, dirty);
  dirty_blocks_.clear();
  *update = mesh_update_t{};
  update->utime = utime;
  update->last_frame_utime = last_frame_utime_;
  update->sequence = mesh_sequence_++;
  update->full = full;
  update->voxel_size_m = options_.map.voxel_size_m;
  if (full) meshed_blocks_.clear();
  for (mesh_block_t& block : lcm_io::meshBlocks(host_map_, blocks, blockMeshOptions())) {
    const BlockIndex index(block.index[0], block.index[1], block.index[2]);
    // An empty block is news only to a receiver that holds a surface for it.
    if (block.num_triangles == 0 && meshed_blocks_.erase(index) == 0) continue;
    if (block.num_triangles > 0) meshed_blocks_.insert(index);
    update->blocks.push_back(std::move(block));
  }
  update->num_blocks = static_cast<std::int32_t>(update->blocks.size());
  return full || update->num_blocks > 0;
}

bool MapperCore::esdfSlice(std::int64_t utime, esdf_slice_t* slice) {
  if (!esdf_ || frames_fused_ == 0) return false;
  esdf_->updateIncremental();
  EsdfMap esdf;
  esdf_->download(esdf);
  *slice = lcm_io::makeEsdfSlice(esdf, options_.esdf_slice_z_m, utime);
  slice->last_frame_utime = last_frame_utime_;
  return true;
}

std::vector<change_event_t> MapperCore::startSession(std::int64_t utime) {
  std::vector<change_event_t> events;
  if (session_active_) events = endSession(utime);
  openSessionIfNeeded();
  return events;
}

std::vector<change_event_t> MapperCore::stopSession(std::int64_t utime) {
  if (!session_active_) throw InputError("no session is open");
  return endSession(utime);
}

std::vector<change_event_t> MapperCore::endSession(std::int64_t utime) {
  session_active_ = false;
  std::vector<change_event_t> events;
  if (!detector_) return events;
  detector_->endSession(session_);
  const std::vector<change::DiscoveredObject> objects =
      change::sessionObjects(*detector_, session_);
  for (const change::DiscoveredObject& object : objects) {
    events.push_back(lcm_io::encodeChangeEvent(object, static_cast<int>(objects.size()), utime));
  }
  return events;
}

TsdfMap MapperCore::downloadMap() {
  TsdfMap map(options_.map);
  fusion_->map().download(map);
  return map;
}

void MapperCore::saveMap(const std::string& path) {
  if (path.empty()) throw InputError("no map path: pass one with the command or --map");
  strata::saveMap(downloadMap(), path);
}

}  // namespace strata::apps
