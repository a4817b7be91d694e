#include "vio_node/vio_core.h"

#include <utility>

namespace strata::apps {
namespace {

constexpr std::int64_t kNsPerUs = 1000;

}  // namespace

VioCore::VioCore(const euroc::Calibration& calibration, odometry::VioPipelineConfig config)
    : pipeline_(calibration, std::move(config)) {}

std::vector<VioPose> VioCore::onFrame(const lcm_io::StereoFrameMsg& frame) {
  return collect(pipeline_.pushFrame(frame.utime * kNsPerUs, frame.left, frame.right));
}

std::vector<VioPose> VioCore::onImu(const lcm_io::ImuMsg& sample) {
  return collect(
      pipeline_.pushImu({sample.utime * kNsPerUs, sample.gyro_rad_s, sample.accel_mps2}));
}

std::vector<VioPose> VioCore::collect(std::vector<odometry::PipelineFrame> frames) {
  std::vector<VioPose> poses;
  for (const odometry::PipelineFrame& f : frames) {
    switch (f.status) {
      case odometry::VioStatus::kTracking:
        poses.push_back({f.timestamp_ns / kNsPerUs, f.T_W_C});
        break;
      case odometry::VioStatus::kFailed:
        last_failure_ = f.reason;
        break;
      case odometry::VioStatus::kInitializing:
        initialising_reason_ = f.reason;
        break;
    }
  }
  return poses;
}

}  // namespace strata::apps
