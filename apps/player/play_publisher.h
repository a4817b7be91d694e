#pragma once
// Sends frames the way a sensor driver would: camera info (first frame and then once a second of
// recording), the pose on the pose channel when not inside the frame, the frame. Shared by
// strata-play, the tests and the benchmark.
// Thread safety: not thread safe.
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "strata/core/types.h"
#include "strata/lcm/convert_frame.h"
#include "strata/sim/sensors/imu.h"
#include "strata/command_t.hpp"

namespace strata::apps {

struct PublisherChannels {
  /// pose "": a frame without its pose in it has none sent either (another process provides it).
  std::string rgbd, camera_info, pose, imu, command;
  static PublisherChannels defaults();
};

class FramePublisher {
 public:
  FramePublisher(lcm::LCM& lcm, const PublisherChannels& channels, const std::string& camera_id,
                 const lcm_io::FrameEncoding& encoding);

  /// Publishes `frame` stamped `utime`; returns the encoded frame's bytes. Throws InputError when
  /// LCM refuses the message.
  std::size_t publish(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                      std::int64_t utime);
  void publishImu(const sim::ImuSample& sample, std::int64_t utime);
  /// Sends a command; returns its request id.
  std::int64_t command(std::int8_t command, const std::string& argument = "");

 private:
  lcm::LCM& lcm_;
  PublisherChannels channels_;
  std::string camera_id_;
  lcm_io::FrameEncoding encoding_;
  std::int64_t sequence_ = 0;
  std::int64_t next_camera_info_utime_ = 0;
  std::int64_t next_request_id_;  // from the clock: unique across players and runs
};

}  // namespace strata::apps
