#include "strata/mapper/mapper.h"

#include <unordered_set>

#include "strata/change/change_detector.h"
#include "strata/core/error.h"
#include "strata/map/map_file.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/select/keyframe_selection.h"

namespace strata {

struct Mapper::Impl {
  // Exactly one of the two owns the device map: the detector (its layers: S = 0, session i =
  // i + 1) when change detection is on, else a plain fusion into layer 0.
  std::unique_ptr<DeviceFusion> fusion;
  std::unique_ptr<change::ChangeDetector> detector;
  DeviceTsdfMap* map = nullptr;  // the owner's device map (stable: both live on the heap)

  std::unique_ptr<DeviceEsdf> esdf;  // follows esdf_layer; recreated when the live layer moves
  int esdf_layer = -1;
  bool esdf_fresh = false;  // esdf has had its first (full) update
  EsdfMap esdf_host;
  std::unique_ptr<EsdfQuery> query;

  std::unique_ptr<RaycastKernel> raycast;
  std::unique_ptr<selection::KeyframeScorer> scorer;

  // Streaming meshes: a host mirror of the live layer, refreshed block by block.
  TsdfMap mesh_mirror;
  int mesh_layer = -1;
  std::unordered_set<BlockIndex, BlockIndexHash> dirty;   // fused since the last stream call
  std::unordered_set<BlockIndex, BlockIndexHash> meshed;  // sent with a surface

  explicit Impl(const MapConfig& map) : mesh_mirror(map) {}
};

Mapper::Mapper(const MapperConfig& config, vk::Context& context)
    : config_(config), context_(context) {
  config_.validate();
  impl_ = std::make_unique<Impl>(config_.map);
  if (config_.change_detection) {
    impl_->detector = std::make_unique<change::ChangeDetector>(context_, config_.map,
                                                               config_.change);
  } else {
    impl_->fusion = std::make_unique<DeviceFusion>(context_, config_.map);
  }
  impl_->map = &liveFusion().map();
  // Touched blocks drive the incremental ESDF and the mesh stream.
  liveFusion().setTrackTouchedBlocks(true);
  if (config_.keyframe_scoring) {
    impl_->scorer = std::make_unique<selection::KeyframeScorer>(context_, config_.scorer);
  }
}

Mapper::~Mapper() = default;

DeviceFusion& Mapper::liveFusion() {
  return impl_->detector ? *impl_->detector->deviceFusion() : *impl_->fusion;
}

DeviceTsdfMap& Mapper::deviceMap() { return *impl_->map; }

int Mapper::liveLayer() const {
  if (!impl_->detector || !session_open_) return 0;
  return impl_->detector->sessionLayer(sessions_ - 1);
}

std::uint32_t Mapper::blockCount() const { return impl_->map->blockCount(); }

void Mapper::openSessionIfNeeded() {
  if (session_open_) return;
  // The detector numbers its sessions as this count does (a loaded map is its session 0).
  if (impl_->detector) impl_->detector->beginSession();
  ++sessions_;
  session_open_ = true;
  session_frames_ = 0;
}

int Mapper::beginSession() {
  if (session_open_) endSession();
  openSessionIfNeeded();
  return sessions_ - 1;
}

void Mapper::discoverObjects(SessionResult& result) {
  if (!config_.keep_session_evidence) {
    result.objects = change::sessionObjects(*impl_->detector, result.session, config_.objects);
    return;
  }
  TsdfMap session_map(config_.map);
  result.objects = change::sessionObjects(*impl_->detector, result.session, config_.objects,
                                          &session_map, &result.surface);
  result.session_map = std::move(session_map);
}

SessionResult Mapper::endSession() {
  if (!session_open_) throw InputError("endSession: no session is open");
  SessionResult result;
  result.session = sessions_ - 1;
  result.frames = session_frames_;
  session_open_ = false;
  if (impl_->detector) {
    result.update = impl_->detector->endSession(result.session);
    if (config_.discover_objects) {
      discoverObjects(result);
    }
    if (config_.release_ended_sessions) impl_->detector->releaseSession(result.session);
  }
  return result;
}

SessionResult Mapper::addSessionMap(const TsdfMap& map) {
  if (!impl_->detector) throw InputError("addSessionMap: change detection is off");
  if (session_open_) throw InputError("addSessionMap: a session is open; end it first");
  SessionResult result;
  result.session = impl_->detector->addSessionMap(map);
  ++sessions_;
  result.update = impl_->detector->endSession(result.session);
  if (config_.discover_objects) {
    discoverObjects(result);
  }
  impl_->esdf_fresh = false;  // S changed in every block the map holds
  return result;
}

change::ChangeDetector& Mapper::changeDetector() {
  if (!impl_->detector) throw InputError("changeDetector: change detection is off");
  return *impl_->detector;
}

TsdfMap Mapper::staticMap() {
  if (impl_->detector) return impl_->detector->staticMap();
  return download();
}

IntegrateStats Mapper::integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                 const Eigen::Isometry3d& T_W_C) {
  // NOTE: fusion reads the pose from the frame, so an explicit pose costs a copy of the images.
  RgbdFrame posed = frame;
  posed.T_W_C = T_W_C;
  return integrate(posed, intrinsics);
}

IntegrateStats Mapper::integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics) {
  validatePose(frame.T_W_C, "integrate: T_W_C");
  openSessionIfNeeded();
  IntegrateStats stats;
  stats.fusion = impl_->detector
                     ? impl_->detector->integrate(sessions_ - 1, frame, intrinsics)
                     : impl_->fusion->integrate(frame, intrinsics);
  const std::vector<BlockIndex>& touched = liveFusion().lastTouchedBlocks();
  impl_->dirty.insert(touched.begin(), touched.end());
  if (impl_->esdf && impl_->esdf_layer == liveLayer()) impl_->esdf->markDirty(touched);
  ++frames_;
  ++session_frames_;
  stats.blocks = blockCount();
  return stats;
}

void Mapper::requireEsdf(const char* what) const {
  if (!config_.esdf) throw InputError(std::string(what) + ": the ESDF is off (MapperConfig::esdf)");
}

EsdfUpdateStats Mapper::updateEsdf() {
  requireEsdf("updateEsdf");
  const int layer = liveLayer();
  if (!impl_->esdf || impl_->esdf_layer != layer) {
    EsdfConfig esdf_config = config_.esdf_config;
    esdf_config.tsdf_layer = layer;
    impl_->esdf = std::make_unique<DeviceEsdf>(context_, deviceMap(), esdf_config);
    impl_->esdf_layer = layer;
    impl_->esdf_fresh = false;
    impl_->query.reset();
  }
  const EsdfUpdateStats stats =
      impl_->esdf_fresh ? impl_->esdf->updateIncremental() : impl_->esdf->updateAll();
  impl_->esdf_fresh = true;
  impl_->query.reset();  // the host copy is made on the first query after the update
  return stats;
}

const EsdfQuery& Mapper::query() const {
  requireEsdf("ESDF query");
  if (!impl_->esdf_fresh) throw InputError("ESDF query: call updateEsdf() first");
  if (!impl_->query) {
    impl_->esdf->download(impl_->esdf_host);
    impl_->query = std::make_unique<EsdfQuery>(impl_->esdf_host);
  }
  return *impl_->query;
}

const EsdfMap& Mapper::esdf() const { return query().map(); }

DeviceEsdf* Mapper::deviceEsdf() {
  requireEsdf("deviceEsdf");
  return impl_->esdf_fresh && impl_->esdf_layer == liveLayer() ? impl_->esdf.get() : nullptr;
}

EsdfSample Mapper::distance(const Eigen::Vector3f& p_W) const {
  return query().sample(p_W);
}

std::vector<EsdfSample> Mapper::distances(const std::vector<Eigen::Vector3f>& points_W) const {
  return query().sample(points_W);
}

Eigen::Vector3f Mapper::gradient(const Eigen::Vector3f& p_W) const { return distance(p_W).gradient; }

bool Mapper::isPointFree(const Eigen::Vector3f& p_W, float margin_m,
                         UnknownPolicy unknown) const {
  return isSphereFree(p_W, 0.0f, margin_m, unknown);
}

bool Mapper::isSphereFree(const Eigen::Vector3f& centre_W, float radius_m, float margin_m,
                          UnknownPolicy unknown) const {
  return query().isSphereFree(centre_W, radius_m, margin_m, unknown);
}

bool Mapper::isSegmentFree(const Eigen::Vector3f& a_W, const Eigen::Vector3f& b_W,
                           float radius_m, UnknownPolicy unknown) const {
  return query().isSegmentFree(a_W, b_W, radius_m, unknown);
}

bool Mapper::isPathFree(const std::vector<Eigen::Vector3f>& polyline_W, float radius_m,
                        UnknownPolicy unknown) const {
  return query().isPathFree(polyline_W, radius_m, unknown);
}

TsdfMap Mapper::download() {
  TsdfMap map(config_.map);
  deviceMap().download(map, liveLayer());
  return map;
}

Mesh Mapper::mesh(const MeshOptions& options) { return extractMesh(download(), options); }

void Mapper::resetMeshStream() {
  impl_->mesh_layer = -1;
  impl_->meshed.clear();
}

std::vector<BlockMesh> Mapper::meshChangedBlocks(const MeshOptions& options) {
  Impl& impl = *impl_;
  const int layer = liveLayer();
  std::vector<BlockIndex> blocks;
  if (impl.mesh_layer != layer) {
    // First call, or the live layer moved (a new session): everything is news.
    impl.mesh_mirror = TsdfMap(config_.map);
    deviceMap().download(impl.mesh_mirror, layer);
    blocks = impl.mesh_mirror.sortedBlockIndices();
    impl.mesh_layer = layer;
  } else {
    const std::vector<BlockIndex> dirty(impl.dirty.begin(), impl.dirty.end());
    deviceMap().downloadBlocks(dirty, impl.mesh_mirror, layer);
    blocks = blocksToRemesh(impl.mesh_mirror, dirty);
  }
  impl.dirty.clear();
  std::vector<BlockMesh> out;
  for (BlockMesh& block : meshBlocks(impl.mesh_mirror, blocks, options)) {
    // An empty block is news only to a receiver that holds a surface for it.
    if (block.mesh.empty() && impl.meshed.erase(block.index) == 0) continue;
    if (!block.mesh.empty()) impl.meshed.insert(block.index);
    out.push_back(std::move(block));
  }
  return out;
}

RaycastImage Mapper::render(const CameraIntrinsics& camera, const Eigen::Isometry3d& T_W_C,
                            double* device_ms) {
  if (!impl_->raycast) impl_->raycast = std::make_unique<RaycastKernel>(context_);
  RaycastOptions options;
  options.tsdf_layer = liveLayer();
  return impl_->raycast->run(deviceMap(), camera, T_W_C, options, device_ms);
}

KeyframeDecision Mapper::scoreKeyframe(const RgbdFrame& frame,
                                       const CameraIntrinsics& intrinsics) {
  return scoreKeyframe(frame, intrinsics, static_cast<SampleRaycast*>(nullptr));
}

KeyframeDecision Mapper::scoreKeyframe(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                       SampleRaycast* samples) {
  if (!impl_->scorer) {
    throw InputError("scoreKeyframe: keyframe scoring is off (MapperConfig::keyframe_scoring)");
  }
  impl_->scorer->setTsdfLayer(liveLayer());
  KeyframeDecision decision;
  decision.score =
      impl_->scorer->score(deviceMap(), frame, intrinsics, &decision.device_ms, samples);
  decision.reason = selection::keyframeReason(decision.score, config_.keyframe_thresholds);
  decision.keyframe = !decision.reason.empty();
  if (!decision.keyframe) decision.reason = "map already explains the frame";
  return decision;
}

KeyframeDecision Mapper::scoreKeyframe(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                       const Eigen::Isometry3d& T_W_C) {
  validatePose(T_W_C, "scoreKeyframe: T_W_C");
  RgbdFrame posed = frame;
  posed.T_W_C = T_W_C;
  return scoreKeyframe(posed, intrinsics);
}

MapFileContents Mapper::snapshot() {
  MapFileContents contents{download(), std::nullopt, std::nullopt};
  if (!impl_->detector) return contents;
  MapSessionRecord record;
  record.session_open = session_open_;
  record.sessions_ended = static_cast<std::uint32_t>(sessions_ - (session_open_ ? 1 : 0));
  record.session_frames = session_open_ ? session_frames_ : 0;
  record.frames = frames_;
  contents.sessions = record;
  if (session_open_) contents.static_map = impl_->detector->staticMap();
  return contents;
}

void Mapper::save(const std::string& path) {
  if (path.empty()) throw InputError("save: no path given");
  saveMapFile(snapshot(), path);
}

std::unique_ptr<Mapper> Mapper::load(const std::string& path, vk::Context& context,
                                     MapperConfig config) {
  const MapFileContents contents = loadMapFile(path);
  try {
    return resume(contents, context, std::move(config));
  } catch (const InputError& e) {
    throw InputError("map file '" + path + "': " + e.what());
  }
}

std::unique_ptr<Mapper> Mapper::resume(const MapFileContents& contents, vk::Context& context,
                                       MapperConfig config) {
  if (!contents.sessions) return fromMap(contents.map, context, std::move(config));
  const MapSessionRecord& record = *contents.sessions;
  if (!config.change_detection) {
    if (record.session_open) {
      throw InputError("it holds a change-detection session still open, whose layer is that "
                       "session's observations only: continue it with change detection on");
    }
    return fromMap(contents.map, context, std::move(config));  // S, the static world
  }
  config.map.voxel_size_m = contents.map.config().voxel_size_m;
  config.map.truncation_voxels = contents.map.config().truncation_voxels;
  auto mapper = std::make_unique<Mapper>(config, context);
  change::ChangeDetector& detector = *mapper->impl_->detector;
  const TsdfMap& static_map = record.session_open ? *contents.static_map : contents.map;
  detector.restore(static_map, static_cast<int>(record.sessions_ended));
  mapper->sessions_ = static_cast<int>(record.sessions_ended);
  mapper->frames_ = record.frames;
  if (record.session_open) {
    detector.addSessionMap(contents.map);  // begins the open session with its layer so far
    ++mapper->sessions_;
    mapper->session_open_ = true;
    mapper->session_frames_ = record.session_frames;
  }
  return mapper;
}

std::unique_ptr<Mapper> Mapper::fromMap(const TsdfMap& map, vk::Context& context,
                                        MapperConfig config) {
  config.map.voxel_size_m = map.config().voxel_size_m;
  config.map.truncation_voxels = map.config().truncation_voxels;
  auto mapper = std::make_unique<Mapper>(config, context);
  if (mapper->impl_->detector) {
    change::ChangeDetector& detector = *mapper->impl_->detector;
    const int session = detector.addSessionMap(map);
    detector.endSession(session);
    mapper->sessions_ = 1;
  } else {
    mapper->deviceMap().upload(map);
  }
  return mapper;
}

}  // namespace strata
