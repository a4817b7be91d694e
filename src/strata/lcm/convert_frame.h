#pragma once
// rgbd_frame_t <-> RgbdFrame, and decoding of raw LCM payloads that never trusts the sender.
#include <cstdint>
#include <optional>
#include <string>

#include "strata/core/types.h"
#include "strata/command_t.hpp"
#include "strata/pose_t.hpp"
#include "strata/rgbd_frame_t.hpp"

namespace strata::lcm_io {

/// A frame as received: images decoded and size-checked, the pose when the message carried one.
struct ReceivedFrame {
  std::int64_t utime = 0;
  std::string camera_id;
  std::int64_t sequence = 0;
  RgbdFrame frame;  // T_W_C set when has_pose
  bool has_pose = false;
};

struct FrameEncoding {
  /// "depth16" (half the bytes; quantised to 1 / depth_scale m) or "depth32f" (exact).
  std::string depth = "depth16";
  float depth_scale = 5000.0f;
  /// Send the pose inside the frame (true) or leave it to the pose channel (false).
  bool with_pose = true;
};

rgbd_frame_t encodeFrame(const RgbdFrame& frame, std::int64_t utime, const std::string& camera_id,
                         std::int64_t sequence, const FrameEncoding& encoding);

/// Images and pose of a decoded message. Throws InputError naming the problem (encodings, sizes,
/// depth and colour of different sizes, bad pose or pose frames).
ReceivedFrame decodeFrame(const rgbd_frame_t& message);

/// Largest LCM payload decoded, bytes: a 4K frame as depth32f + rgb8 is ~60 MB; checked before
/// decoding so one message cannot make the decoder allocate more than this.
inline constexpr int kMaxPayloadBytes = 256 << 20;

/// Decodes an LCM payload into `message`. Throws InputError when the payload is over
/// kMaxPayloadBytes, the type fingerprint is not Message's, the payload is truncated or has bytes
/// left over, or a size field claims more data than the payload holds (checked first, so garbage
/// cannot make the decoder allocate gigabytes).
template <typename Message>
void decodePayload(const void* data, int size, Message& message);

/// Throws InputError when a length field of a payload claims more bytes than follow it, or a
/// string length is below 1 (called by decodePayload for the types strata-mapper accepts, before
/// lcm-gen's decoder trusts those fields).
void checkRgbdFrameLengths(const std::uint8_t* data, int size);
void checkCameraInfoLengths(const std::uint8_t* data, int size);
void checkPoseLengths(const std::uint8_t* data, int size);
void checkCommandLengths(const std::uint8_t* data, int size);
void checkStereoImageLengths(const std::uint8_t* data, int size);
void checkImuLengths(const std::uint8_t* data, int size);

}  // namespace strata::lcm_io

#include "strata/lcm/decode_payload_impl.h"
