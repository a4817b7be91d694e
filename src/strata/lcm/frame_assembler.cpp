#include "strata/lcm/frame_assembler.h"

#include "strata/core/error.h"

namespace strata::lcm_io {

FrameAssembler::FrameAssembler(const AssemblerConfig& config)
    : config_(config), poses_(config.pose_capacity, config.max_pose_gap_us) {}

void FrameAssembler::onCameraInfo(const std::string& camera_id,
                                  const CameraIntrinsics& intrinsics) {
  intrinsics.validate();
  cameras_[camera_id] = intrinsics;
}

AssemblerOutput FrameAssembler::onPose(std::int64_t utime, const Eigen::Isometry3d& T_W_C) {
  validatePose(T_W_C, "pose at utime " + std::to_string(utime));
  poses_.add(utime, T_W_C);
  AssemblerOutput out;
  resolvePending(out);
  return out;
}

AssemblerOutput FrameAssembler::onFrame(ReceivedFrame received) {
  const auto camera = cameras_.find(received.camera_id);
  if (camera == cameras_.end()) {
    throw InputError("frame at utime " + std::to_string(received.utime) +
                     ": no camera_info for camera '" + received.camera_id + "' yet");
  }
  const auto last = last_frame_utime_.find(received.camera_id);
  if (last != last_frame_utime_.end() && received.utime <= last->second) {
    throw InputError("frame utime " + std::to_string(received.utime) + " of camera '" +
                     received.camera_id + "' is not after its previous frame's " +
                     std::to_string(last->second) + " (out of order)");
  }
  validateFrame(received.frame, camera->second);
  last_frame_utime_[received.camera_id] = received.utime;

  ReadyFrame frame{received.utime, 0, std::move(received.frame), camera->second};
  AssemblerOutput out;
  if (received.has_pose) {
    out.ready.push_back(std::move(frame));
    return out;
  }
  pending_.push_back(std::move(frame));
  while (pending_.size() > config_.max_pending_frames) {
    dropNoPose(pending_.front(), PoseLookup::kNotYet, out);
    pending_.pop_front();
  }
  resolvePending(out);
  return out;
}

void FrameAssembler::resolvePending(AssemblerOutput& out) {
  while (!pending_.empty()) {
    ReadyFrame& frame = pending_.front();
    const PoseLookup lookup = poses_.lookup(frame.utime, &frame.frame.T_W_C);
    if (lookup == PoseLookup::kNotYet) return;  // wait for a newer pose
    if (lookup == PoseLookup::kFound) {
      out.ready.push_back(std::move(frame));
    } else {
      dropNoPose(frame, lookup, out);
    }
    pending_.pop_front();
  }
}

void FrameAssembler::dropNoPose(const ReadyFrame& frame, PoseLookup why,
                                AssemblerOutput& out) const {
  ++out.dropped_no_pose;
  out.drop_reasons.push_back("frame at utime " + std::to_string(frame.utime) +
                             " dropped: no pose (" + describe(why) + ")");
}

}  // namespace strata::lcm_io
