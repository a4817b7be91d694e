#pragma once
// The two implementations behind ChangeDetector (internal): the device (DeviceFusion +
// DeviceChange over layers of one DeviceTsdfMap) and the C++ reference on host maps. ChangeDetector
// checks session indices and order; a backend only does the work.
#include <memory>

#include "strata/change/change_types.h"
#include "strata/core/types.h"
#include "strata/integrate/device_fusion.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata::change {

class ChangeBackend {
 public:
  virtual ~ChangeBackend() = default;
  /// Adds the layers of session number `session` (= the number of sessions so far), reusing
  /// released ones (cleared) where there are.
  virtual void addSession(int session) = 0;
  /// Frees the layers of an ended session for a later addSession.
  virtual void releaseSession(int session) = 0;
  /// S := static_map, and `ended_sessions` sessions that ended and were released (no layers).
  virtual void restore(const TsdfMap& static_map, int ended_sessions) = 0;
  /// TSDF layer of `session` in deviceMap(); -1 without a device map.
  virtual int sessionTsdfLayer(int /*session*/) const { return -1; }
  virtual FrameStats integrate(int session, const RgbdFrame& frame,
                               const CameraIntrinsics& intrinsics) = 0;
  virtual void setSessionMap(int session, const TsdfMap& map) = 0;
  /// Steps 2-5 for `session`: D, S and the session's dynamic part.
  virtual ChangeUpdateStats update(int session) = 0;
  /// Recomputes the dynamic part of an ended session against the current S.
  virtual void refreshDynamic(int session) = 0;
  virtual TsdfMap staticMap() = 0;
  virtual TsdfMap sessionMap(int session) = 0;
  virtual LabelMap labels() = 0;
  virtual LabelMap sessionDynamic(int session) = 0;
  virtual DeviceTsdfMap* deviceMap() { return nullptr; }
  virtual DeviceFusion* deviceFusion() { return nullptr; }
};

std::unique_ptr<ChangeBackend> makeDeviceBackend(vk::Context& context, const MapConfig& map_config,
                                                 const ChangeConfig& config);
std::unique_ptr<ChangeBackend> makeReferenceBackend(const MapConfig& map_config,
                                                    const ChangeConfig& config);

}  // namespace strata::change
