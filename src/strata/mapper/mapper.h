#pragma once
// strata::Mapper — the one object a program calls to map: it owns the device map and its layers
// (TSDF, optional ESDF, the session layers and static estimate of change detection) and borrows
// them to the kernels of each capability.
//
//   vk::Context context = vk::Context::create({});
//   Mapper mapper(MapperConfig{}, context);
//   for (const RgbdFrame& frame : frames) mapper.integrate(frame, intrinsics);
//   mapper.updateEsdf();                 // with config.esdf
//   Mesh mesh = mapper.mesh();
//   mapper.save("room.strata");
//
// Frames: T_W_C maps camera to world (metres); the camera looks down +z. Layers during a session
// with change detection on: integrate() fuses into the session's own layer, once; the static
// estimate S changes only at endSession(). "The live layer" below is that session layer, or the
// one TSDF layer when change detection is off; between sessions with change detection on it is S.
// Errors: bad input throws InputError before anything changes; a full device or block budget
// throws DeviceError and refuses the frame whole: the map is exactly as before it, and save()
// still works (docs/faults.md).
// Thread safety: not thread safe; one Mapper per thread (the context may be shared only when
// calls never overlap).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "strata/change/object_discovery.h"
#include "strata/core/types.h"
#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_query.h"
#include "strata/integrate/device_fusion.h"
#include "strata/map/map_file.h"
#include "strata/map/tsdf_map.h"
#include "strata/mapper/mapper_config.h"
#include "strata/mesh/block_meshes.h"
#include "strata/mesh/mesh.h"
#include "strata/raycast/raycast.h"
#include "strata/select/keyframe_scorer.h"
#include "strata/track/rgbd_tracker.h"
#include "strata/vk/vk.h"

namespace strata {
namespace change {
class ChangeDetector;
}

/// What integrate() did to one frame.
struct IntegrateStats {
  FrameStats fusion;           // device times per kernel, blocks touched
  std::uint32_t blocks = 0;    // allocated blocks after the frame (all layers share them)
};

/// The decision of scoreKeyframe(): the metrics and whether the frame is worth fusing.
struct KeyframeDecision {
  selection::KeyframeScore score;
  bool keyframe = false;
  std::string reason;  // the first metric over its threshold, or why none is
  double device_ms = 0.0;
};

/// What endSession() found.
struct SessionResult {
  int session = 0;
  std::vector<change::DiscoveredObject> objects;  // moved or added, world frame; empty w/o change
  change::ChangeUpdateStats update;               // stage times of the merge (change detection)
  std::size_t frames = 0;                         // fused in the session
  /// With MapperConfig::keep_session_evidence (and objects discovered): the session's own map
  /// (world frame) and its surface with the face labels the objects were cut from; else empty.
  std::optional<TsdfMap> session_map;
  change::LabelledSurface surface;
};

/// What trackAndIntegrate() did with one frame.
struct TrackedFrame {
  TrackResult track;          // pose (camera to world), status, figures
  bool fused = false;         // false when the frame was lost (the map is unchanged)
  IntegrateStats integrate;   // of the fusion, when fused
};

class Mapper {
 public:
  /// `context` must outlive the mapper. Validates `config` (InputError naming the field).
  Mapper(const MapperConfig& config, vk::Context& context);
  ~Mapper();
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  /// Fuses one frame at frame.T_W_C into the live layer (opening a session when none is open).
  IntegrateStats integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics);
  /// The same at `T_W_C` (frame.T_W_C is ignored).
  IntegrateStats integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                           const Eigen::Isometry3d& T_W_C);

  /// Brings the ESDF of the live layer up to date: only the blocks fused since the last update
  /// and those within reach of them (a full pass the first time, or after the live layer
  /// changed). InputError without config.esdf.
  EsdfUpdateStats updateEsdf();
  /// ESDF queries on the last updateEsdf() (a host copy, downloaded on the first query after
  /// each update). InputError without config.esdf or before the first update.
  EsdfSample distance(const Eigen::Vector3f& p_W) const;
  std::vector<EsdfSample> distances(const std::vector<Eigen::Vector3f>& points_W) const;
  Eigen::Vector3f gradient(const Eigen::Vector3f& p_W) const;
  /// Collision checks of a sphere robot: free when the distance exceeds radius + margin
  /// everywhere on it; unknown space as `unknown` says.
  bool isPointFree(const Eigen::Vector3f& p_W, float margin_m = 0.0f,
                   UnknownPolicy unknown = UnknownPolicy::kOccupied) const;
  bool isSphereFree(const Eigen::Vector3f& centre_W, float radius_m, float margin_m = 0.0f,
                    UnknownPolicy unknown = UnknownPolicy::kOccupied) const;
  /// The capsule of `radius_m` around a segment / around every segment of a polyline.
  bool isSegmentFree(const Eigen::Vector3f& a_W, const Eigen::Vector3f& b_W, float radius_m,
                     UnknownPolicy unknown = UnknownPolicy::kOccupied) const;
  bool isPathFree(const std::vector<Eigen::Vector3f>& polyline_W, float radius_m,
                  UnknownPolicy unknown = UnknownPolicy::kOccupied) const;
  /// The ESDF of the last update (the host copy the queries read).
  const EsdfMap& esdf() const;
  /// The ESDF on the device as of the last updateEsdf(), for batched device queries
  /// (EsdfQueryKernel) without downloading it; nullptr before the first update. Valid until the
  /// next updateEsdf() or session change.
  DeviceEsdf* deviceEsdf();

  /// Mesh of the live layer (downloads it: device -> host).
  Mesh mesh(const MeshOptions& options = {});
  /// Meshes of the blocks whose surface may have changed since the last call (fused blocks and
  /// their neighbours); the first call returns every block with a surface.
  /// Blocks that never held a surface and still hold none are left out; a block that lost its
  /// surface comes with an empty mesh (so a viewer drops it). Block meshes carry no normals.
  std::vector<BlockMesh> meshChangedBlocks(const MeshOptions& options = {});
  /// The next meshChangedBlocks() returns every block with a surface (a viewer joined late).
  void resetMeshStream();
  /// Renders the live layer from T_W_C (device raycast).
  RaycastImage render(const CameraIntrinsics& camera, const Eigen::Isometry3d& T_W_C,
                      double* device_ms = nullptr);

  /// Tracks `frame` (its depth; frame.T_W_C is ignored) against the live layer from T_W_C_guess:
  /// frame-to-model ICP (track/rgbd_tracker.h, config.track). The map is not changed.
  TrackResult track(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                    const Eigen::Isometry3d& T_W_C_guess);
  /// Odometry and fusion of a sequence without poses: the guess is the constant-velocity
  /// prediction of the frames tracked before (MotionModel); a frame tracked ok is fused at its
  /// estimate, a lost one is not fused (and the next frame is tried from the last good pose).
  /// The first call fuses at frame.T_W_C when the map is empty (that frame defines the world:
  /// give identity, or a known first pose); on a map that is not empty it tracks from it.
  TrackedFrame trackAndIntegrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics);

  /// Opens a session (ending an open one first). Returns its index (0, 1, ...).
  int beginSession();
  /// Ends the open session: with change detection, merges it into the static estimate and
  /// returns the objects that moved. InputError when no session is open.
  SessionResult endSession();
  /// With change detection on and no session open: a saved map (e.g. another day's) as the next
  /// session, ended at once: merged into S, its objects discovered (discover_objects). Its voxel
  /// size and truncation must match config.map's (InputError otherwise).
  SessionResult addSessionMap(const TsdfMap& map);
  bool sessionOpen() const { return session_open_; }
  int sessionCount() const { return sessions_; }
  /// The static estimate S (host copy; with change detection, after the last endSession()).
  TsdfMap staticMap();

  /// Scores `frame` (at frame.T_W_C) against the live layer as it is before the frame is fused.
  /// InputError without config.keyframe_scoring.
  KeyframeDecision scoreKeyframe(const RgbdFrame& frame, const CameraIntrinsics& intrinsics);
  KeyframeDecision scoreKeyframe(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                 const Eigen::Isometry3d& T_W_C);
  /// The same, also returning the sample raycast the metrics came from (per-sample hits and
  /// depths, for programs that compare the frame with the map sample by sample).
  KeyframeDecision scoreKeyframe(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                 SampleRaycast* samples);

  /// Host copy of the live layer (device -> host).
  TsdfMap download();
  /// What save() writes (device -> host): the live layer; with change detection also where the
  /// sessions stand and, while a session is open, the static estimate S (map/map_file.h).
  MapFileContents snapshot();
  /// Writes snapshot() atomically (versioned, checksummed; map/map_file.h): a plain map (format
  /// version 1) without change detection, a mapper state (version 2) with it.
  void save(const std::string& path);
  /// A mapper that continues from a saved file: a mapper state (version 2) resumes exactly where
  /// the saving mapper stood (S, the open session's layer, the session count), so frames fused
  /// after it give the map an uninterrupted mapper would have; a plain map is loaded as
  /// fromMap() does. The file's voxel size and truncation replace config.map's. InputError naming
  /// the file when it cannot be read, and for a mapper state with an open session when `config`
  /// has change detection off (its live layer is one session's observations only).
  static std::unique_ptr<Mapper> load(const std::string& path, vk::Context& context,
                                      MapperConfig config = {});
  /// The same from a file's contents (e.g. read already to report on them).
  static std::unique_ptr<Mapper> resume(const MapFileContents& contents, vk::Context& context,
                                        MapperConfig config = {});
  /// The same from a map in memory (e.g. one already read for other uses).
  static std::unique_ptr<Mapper> fromMap(const TsdfMap& map, vk::Context& context,
                                         MapperConfig config = {});

  const MapperConfig& config() const { return config_; }
  std::size_t framesIntegrated() const { return frames_; }
  std::uint32_t blockCount() const;
  /// The device map (all layers) and its fusion, for kernels the facade does not wrap.
  DeviceTsdfMap& deviceMap();
  /// TSDF layer of the device map integrate() writes now.
  int liveLayer() const;
  /// The change detector that owns the layers (config.change_detection; InputError otherwise),
  /// for work between integrate() and endSession() the facade does not wrap (editing a session's
  /// layer, a session's own map and dynamic part).
  change::ChangeDetector& changeDetector();

 private:
  struct Impl;
  void openSessionIfNeeded();
  /// Objects of the ended session result.session (and its evidence when kept).
  void discoverObjects(SessionResult& result);
  DeviceFusion& liveFusion();
  void requireEsdf(const char* what) const;
  const EsdfQuery& query() const;

  MapperConfig config_;
  vk::Context& context_;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<RgbdTracker> tracker_;  // made on the first track()
  MotionModel motion_;                    // of trackAndIntegrate()
  std::size_t frames_ = 0;
  std::size_t session_frames_ = 0;
  int sessions_ = 0;
  bool session_open_ = false;
};

}  // namespace strata
