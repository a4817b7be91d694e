#pragma once
// strata::RgbdTracker — the pose of an RGB-D frame against the map (frame-to-model ICP, like
// KinectFusion): the map is raycast at the guess; the live depth's pyramid is aligned to that
// model coarse to fine by point-to-plane Gauss-Newton (normal_equations.h on the device, the
// solve in double on the host, gauss_newton.h). The result says whether the frame is lost
// (TrackConfig's failure rules); a lost frame's pose must not be fused.
//
//   RgbdTracker tracker(context, TrackConfig{});
//   TrackResult r = tracker.track(mapper.deviceMap(), mapper.liveLayer(), frame, intrinsics,
//                                 motion.predict());
//   if (r.ok()) { mapper.integrate(frame, intrinsics, r.T_W_C); motion.accept(r.T_W_C); }
//   else motion.lost();
//
// Frames: T_W_C camera to world, metres. frame.T_W_C is ignored. The map is only read.
// Errors: InputError for a frame that does not match the intrinsics or a bad config.
// Thread safety: not thread safe; one tracker per thread and context.
#include "strata/core/types.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/raycast/raycast.h"
#include "strata/track/normal_equations.h"
#include "strata/track/track_config.h"
#include "strata/vk/vk.h"

namespace strata {

class RgbdTracker {
 public:
  /// Validates `config` (InputError naming the field). `context` must outlive the tracker.
  RgbdTracker(vk::Context& context, const TrackConfig& config = {});

  /// Aligns `frame`'s depth to TSDF layer `tsdf_layer` of `map` starting from T_W_C_guess.
  TrackResult track(DeviceTsdfMap& map, int tsdf_layer, const RgbdFrame& frame,
                    const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_C_guess);

  const TrackConfig& config() const { return config_; }

 private:
  AssociationGates gatesFor() const;
  /// Applies the failure rules to a finished estimate (fills status and reason).
  void judge(const Eigen::Isometry3d& T_W_C_guess, TrackResult* result) const;

  TrackConfig config_;
  RaycastKernel raycast_;
  NormalEquationsKernel equations_;
};

/// Constant-velocity motion model: the guess for the next frame is the last good pose moved by
/// the last good motion; after a lost frame the guess is the last good pose (no motion) until two
/// consecutive frames are tracked again.
class MotionModel {
 public:
  bool initialised() const { return initialised_; }
  Eigen::Isometry3d predict() const;
  void accept(const Eigen::Isometry3d& T_W_C);
  void lost();
  /// Forgets everything (the next accept() starts again).
  void reset() { *this = MotionModel(); }

 private:
  bool initialised_ = false;
  bool has_velocity_ = false;
  bool after_loss_ = false;  // the next accept() starts a new velocity estimate
  Eigen::Isometry3d last_T_W_C_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d velocity_ = Eigen::Isometry3d::Identity();  // T_C(k-1)_C(k) of the last step
};

}  // namespace strata
