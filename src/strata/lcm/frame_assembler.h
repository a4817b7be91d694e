#pragma once
// Turns received frames, poses and camera infos into frames ready to fuse: intrinsics by camera
// id, the pose from the frame or interpolated from the pose channel (frames newer than the newest
// pose wait, bounded, for the pose after them), stamps checked for order, sizes checked against
// the intrinsics. Plain C++ (no LCM), so every rule is testable.
// Thread safety: not thread safe (the mapper calls it from its receive thread only).
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/pose_buffer.h"

namespace strata::lcm_io {

struct ReadyFrame {
  std::int64_t utime = 0;
  /// Order of arrival among the frames and commands the mapper queued (set when queued), so a
  /// command runs after the frames received before it.
  std::uint64_t arrival = 0;
  RgbdFrame frame;  // with T_W_C
  CameraIntrinsics intrinsics;
};

struct AssemblerConfig {
  /// Frames waiting for a newer pose; beyond this the oldest is dropped (no pose).
  std::size_t max_pending_frames = 30;
  /// Poses kept for interpolation, and the longest gap interpolated across.
  std::size_t pose_capacity = 4096;
  std::int64_t max_pose_gap_us = 500000;
};

struct AssemblerOutput {
  std::vector<ReadyFrame> ready;
  std::size_t dropped_no_pose = 0;
  std::vector<std::string> drop_reasons;  // one per dropped frame, for the log
};

class FrameAssembler {
 public:
  explicit FrameAssembler(const AssemblerConfig& config = {});

  /// Throws InputError for a bad calibration (nothing changes).
  void onCameraInfo(const std::string& camera_id, const CameraIntrinsics& intrinsics);
  /// Throws InputError for an out-of-order pose; otherwise releases frames now bracketed.
  AssemblerOutput onPose(std::int64_t utime, const Eigen::Isometry3d& T_W_C);
  /// Throws InputError (the frame is rejected) for: no camera_info for its camera yet, sizes that
  /// disagree with it, a stamp not after the previous frame's, a bad pose.
  AssemblerOutput onFrame(ReceivedFrame received);

  std::size_t pendingFrames() const { return pending_.size(); }

 private:
  void resolvePending(AssemblerOutput& out);
  void dropNoPose(const ReadyFrame& frame, PoseLookup why, AssemblerOutput& out) const;

  AssemblerConfig config_;
  std::map<std::string, CameraIntrinsics> cameras_;
  PoseBuffer poses_;
  std::deque<ReadyFrame> pending_;                        // no pose yet, oldest first
  std::map<std::string, std::int64_t> last_frame_utime_;  // per camera: stamps must increase
};

}  // namespace strata::lcm_io
