// The Mapper's tracking: frames without poses aligned to the live layer, then fused.
#include "strata/mapper/mapper.h"

namespace strata {

TrackResult Mapper::track(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                          const Eigen::Isometry3d& T_W_C_guess) {
  if (!tracker_) tracker_ = std::make_unique<RgbdTracker>(context_, config_.track);
  return tracker_->track(deviceMap(), liveLayer(), frame, intrinsics, T_W_C_guess);
}

TrackedFrame Mapper::trackAndIntegrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics) {
  TrackedFrame out;
  if (!motion_.initialised() && blockCount() == 0) {
    // NOTE: nothing to track against yet: this frame defines the world.
    validatePose(frame.T_W_C, "trackAndIntegrate: first frame T_W_C");
    out.track.status = TrackStatus::kOk;
    out.track.T_W_C = frame.T_W_C;
  } else {
    const Eigen::Isometry3d guess = motion_.initialised() ? motion_.predict() : frame.T_W_C;
    out.track = track(frame, intrinsics, guess);
  }
  if (!out.track.ok()) {
    motion_.lost();
    return out;
  }
  out.integrate = integrate(frame, intrinsics, out.track.T_W_C);
  out.fused = true;
  motion_.accept(out.track.T_W_C);
  return out;
}

}  // namespace strata
