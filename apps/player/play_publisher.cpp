#include "player/play_publisher.h"

#include "strata/core/error.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "strata/imu_t.hpp"
#include "player/internal/publish.h"

namespace strata::apps {
namespace {

constexpr std::int64_t kCameraInfoPeriodUs = 1000000;

using internal::publishOrThrow;

}  // namespace

PublisherChannels PublisherChannels::defaults() {
  return {lcm_io::kRgbdChannel, lcm_io::kCameraInfoChannel, lcm_io::kPoseChannel,
          lcm_io::kImuChannel, lcm_io::kCommandChannel};
}

FramePublisher::FramePublisher(lcm::LCM& lcm, const PublisherChannels& channels,
                               const std::string& camera_id, const lcm_io::FrameEncoding& encoding)
    : lcm_(lcm),
      channels_(channels),
      camera_id_(camera_id),
      encoding_(encoding),
      next_request_id_(lcm_io::nowUtime()) {
  if (!lcm_.good()) throw InputError("LCM could not be opened");
}

std::size_t FramePublisher::publish(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                    std::int64_t utime) {
  if (sequence_ == 0 || utime >= next_camera_info_utime_) {
    publishOrThrow(lcm_, channels_.camera_info,
                   lcm_io::encodeCameraInfo(intrinsics, camera_id_, utime));
    next_camera_info_utime_ = utime + kCameraInfoPeriodUs;
  }
  if (!encoding_.with_pose && !channels_.pose.empty()) {
    publishOrThrow(lcm_, channels_.pose, lcm_io::encodePose(frame.T_W_C, utime));
  }
  const rgbd_frame_t message =
      lcm_io::encodeFrame(frame, utime, camera_id_, sequence_++, encoding_);
  publishOrThrow(lcm_, channels_.rgbd, message);
  return static_cast<std::size_t>(message.getEncodedSize());
}

void FramePublisher::publishImu(const sim::ImuSample& sample, std::int64_t utime) {
  imu_t message{};
  message.utime = utime;
  message.frame = "imu";
  for (int a = 0; a < 3; ++a) {
    message.angular_velocity[a] = sample.gyro_rad_s[a];
    message.linear_acceleration[a] = sample.accel_mps2[a];
  }
  publishOrThrow(lcm_, channels_.imu, message);
}

std::int64_t FramePublisher::command(std::int8_t command, const std::string& argument) {
  command_t message{};
  message.utime = lcm_io::nowUtime();
  message.request_id = next_request_id_++;
  message.command = command;
  message.argument = argument;
  publishOrThrow(lcm_, channels_.command, message);
  return message.request_id;
}

}  // namespace strata::apps
