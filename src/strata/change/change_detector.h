#pragma once
// Multi-session change detection (docs/change.md, steps 1-5). Every session is fused into
// its own TSDF layer M_i (layers share one block index); a static estimate S and a label grid D
// are kept up to date session by session:
//   endSession(N): D = erosion-then-dilation of difference(S, M_N); S = mergeStatic(S, M_N, D);
//   P_N = the cleaned-up sessionDynamicLabel(M_N, S).
//   sessionDynamic(i) of an earlier session is recomputed against the current S when S changed
//   since (a session that ends later may reveal that session i's object was not static).
// The exact per-voxel rules are in change_rules.h. Properties that follow from them:
// S starts as the first session's observed voxels; with noise-free, aligned sessions S is the
// voxel-wise max of the observed session values; nothing is labelled where the layers compared
// are unobserved (partial overlap); floor first seen in a later session enters S.
// NOTE: set MapConfig::allocate_free_space: without it the free space away from surfaces is never
// observed, so S cannot tell the parts of a new object that stand in such space from new static
// space (they enter S, and the object's part P_N misses them).
// Thread safety: not thread safe; one ChangeDetector per thread.
#include <memory>

#include "strata/change/change_types.h"
#include "strata/core/types.h"
#include "strata/integrate/device_fusion.h"
#include "strata/map/map_config.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata::change {

class ChangeBackend;

class ChangeDetector {
 public:
  /// Device mode: fusion and every pass on `context`'s device (which must outlive this object).
  /// Throws InputError for an invalid config.
  ChangeDetector(vk::Context& context, const MapConfig& map_config, const ChangeConfig& config);
  /// Reference mode: the same API on the host (C++ reference fusion and passes), for tests and
  /// benchmarks. Stage times are host wall times.
  ChangeDetector(const MapConfig& map_config, const ChangeConfig& config);
  ~ChangeDetector();
  ChangeDetector(ChangeDetector&&) noexcept;
  ChangeDetector& operator=(ChangeDetector&&) noexcept;

  /// Starts a session (a TSDF layer of its own, every voxel unobserved); returns its index
  /// (0, 1, ... in order). Sessions may be fused in any order but end in the order they began.
  int beginSession();
  /// Fuses one frame into `session` (begun, not ended). Throws InputError for a bad session or
  /// frame before anything changes.
  FrameStats integrate(int session, const RgbdFrame& frame, const CameraIntrinsics& intrinsics);
  /// Continues a detector that was saved (a mapper's state, map_file.h): S becomes `static_map`
  /// (same voxel size and truncation) and sessions 0 .. ended_sessions-1 count as ended and
  /// released, so the next beginSession() returns `ended_sessions`. Only on a detector without
  /// sessions (InputError otherwise, before anything changes). D is empty until the next
  /// endSession().
  void restore(const TsdfMap& static_map, int ended_sessions);
  /// Begins a session whose layer is `session_map` (a saved map with the same voxel size and
  /// truncation); returns its index. It still needs endSession.
  int addSessionMap(const TsdfMap& session_map);
  /// Replaces the layer of `session` (begun, not ended) with `session_map` (same voxel size and
  /// truncation): for host-side edits of a layer before it ends, such as carrying observations
  /// forward (carry_forward.h). Throws InputError for a bad session or map before anything changes.
  void replaceSessionMap(int session, const TsdfMap& session_map);
  /// Merges `session` (the next one to end) into S, recomputes D and the session's dynamic part
  /// (steps 2-5). Stage times: device ms from timestamp queries (host ms in reference mode).
  ChangeUpdateStats endSession(int session);

  /// Explicit copies to the host. staticMap: S. sessionMap: M_session.
  TsdfMap staticMap();
  TsdfMap sessionMap(int session);
  /// D of the last endSession (kUnknown where S or that session was unobserved).
  LabelMap labels();
  /// P_session against the current S (recomputed first when S changed since it was computed);
  /// `session` must have ended. kDynamic: the session had something there that S does not (moved
  /// or added objects as they stood then); kUnknown where the session was unobserved.
  LabelMap sessionDynamic(int session);

  int sessionCount() const { return static_cast<int>(sessions_.size()); }
  int endedSessionCount() const { return ended_; }
  bool referenceMode() const { return reference_; }
  const MapConfig& mapConfig() const { return map_config_; }
  const ChangeConfig& config() const { return config_; }
  /// The device map (S is TSDF layer 0, so raycasts and the ESDF see the static world);
  /// nullptr in reference mode.
  DeviceTsdfMap* deviceMap();
  /// The fusion into the device map (touched-block tracking for incremental consumers);
  /// nullptr in reference mode.
  DeviceFusion* deviceFusion();
  /// TSDF layer of `session` (begun, not released) in deviceMap() (S is layer 0); -1 in
  /// reference mode.
  int sessionLayer(int session) const;
  /// Frees the layers of an ended session (a TSDF and a label layer, one block pool each); the
  /// next session reuses them, so a mapper that runs session after session keeps its memory
  /// bounded. Its sessionMap and sessionDynamic are gone then (InputError). Throws InputError
  /// when the session has not ended or was released already.
  void releaseSession(int session);

 private:
  struct Session {
    bool ended = false;
    bool released = false;
    int part_version = -1;  // ended_ when its dynamic part was computed
  };
  void requireSession(int session, const char* what) const;
  /// requireSession, and its layers not released.
  void requireLayers(int session, const char* what) const;
  void requireSameGrid(const TsdfMap& session_map, const char* what) const;

  MapConfig map_config_;
  ChangeConfig config_;
  bool reference_ = false;
  std::unique_ptr<ChangeBackend> backend_;
  std::vector<Session> sessions_;
  int ended_ = 0;
};

}  // namespace strata::change
