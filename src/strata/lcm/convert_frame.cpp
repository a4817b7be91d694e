#include "strata/lcm/convert_frame.h"

#include "strata/core/error.h"
#include "strata/lcm/convert_image.h"
#include "strata/lcm/convert_pose.h"

namespace strata::lcm_io {
namespace {

/// Walks an LCM payload (big-endian) far enough to check the length fields.
class WireReader {
 public:
  WireReader(const std::uint8_t* data, int size, const char* type)
      : data_(data), size_(size), type_(type) {}
  void skip(int bytes) {
    if (bytes < 0 || bytes > size_ - pos_) fail("truncated");
    pos_ += bytes;
  }
  std::int32_t readInt32() {
    skip(4);
    const std::uint8_t* p = data_ + pos_ - 4;
    return static_cast<std::int32_t>((std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) |
                                     (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]});
  }
  /// NOTE: an LCM string's length counts its terminating NUL, so it is at least 1; lcm-gen's
  /// decoders compute `length - 1` unchecked (signed overflow for INT32_MIN, a huge size for 0).
  void skipString() {
    const std::int32_t length = readInt32();
    if (length < 1) fail("string length " + std::to_string(length) + " (at least 1: its NUL)");
    skip(checkedLength(length, 1, "string"));
  }
  /// A length field counting `element_bytes`-byte elements; fails when they do not follow.
  int checkedLength(std::int32_t count, int element_bytes, const char* what) {
    if (count < 0 || static_cast<std::int64_t>(count) * element_bytes > size_ - pos_) {
      fail(std::string(what) + " claims " + std::to_string(count) + " elements of " +
           std::to_string(element_bytes) + " bytes, " + std::to_string(size_ - pos_) +
           " bytes left");
    }
    return count * element_bytes;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(std::string(type_) + ": " + why + " at byte " + std::to_string(pos_) + " of " +
                     std::to_string(size_));
  }
  const std::uint8_t* data_;
  int size_;
  const char* type_;
  int pos_ = 0;
};

void skipImage(WireReader& in) {
  in.skip(8);       // utime
  in.skipString();  // encoding
  in.skip(12);      // width, height, depth_scale
  in.skip(in.checkedLength(in.readInt32(), 1, "image data"));
}

RgbdFrame decodeImages(const rgbd_frame_t& message) {
  RgbdFrame frame;
  frame.depth = decodeDepth(message.depth);
  frame.color = decodeColor(message.color);
  if (!frame.color.empty() && (frame.color.width_px != frame.depth.width_px ||
                               frame.color.height_px != frame.depth.height_px)) {
    throw InputError("colour " + std::to_string(frame.color.width_px) + "x" +
                     std::to_string(frame.color.height_px) + " and depth " +
                     std::to_string(frame.depth.width_px) + "x" +
                     std::to_string(frame.depth.height_px) + " differ (register colour to depth)");
  }
  return frame;
}

void skipPose(WireReader& in) {
  in.skip(8);       // utime
  in.skipString();  // parent_frame
  in.skipString();  // child_frame
}

}  // namespace

void checkRgbdFrameLengths(const std::uint8_t* data, int size) {
  WireReader in(data, size, "rgbd_frame_t");
  in.skip(16);  // fingerprint, utime
  in.skipString();
  in.skip(8);  // sequence
  skipImage(in);
  skipImage(in);
  in.skip(1);  // has_pose
  skipPose(in);
}

void checkPoseLengths(const std::uint8_t* data, int size) {
  WireReader in(data, size, "pose_t");
  in.skip(8);  // fingerprint
  skipPose(in);
}

void checkCommandLengths(const std::uint8_t* data, int size) {
  WireReader in(data, size, "command_t");
  in.skip(8 + 8 + 8 + 1);  // fingerprint, utime, request_id, command
  in.skipString();         // argument
}

void checkCameraInfoLengths(const std::uint8_t* data, int size) {
  WireReader in(data, size, "camera_info_t");
  in.skip(16);
  in.skipString();
  in.skip(8 + 32);  // width, height, fx, fy, cx, cy
  in.skipString();
  in.skip(in.checkedLength(in.readInt32(), 8, "distortion"));
}

void checkStereoImageLengths(const std::uint8_t* data, int size) {
  WireReader in(data, size, "stereo_image_t");
  in.skip(8 + 8 + 8);  // fingerprint, utime, sequence
  in.skipString();     // left_camera
  in.skipString();     // right_camera
  skipImage(in);
  skipImage(in);
}

void checkImuLengths(const std::uint8_t* data, int size) {
  WireReader in(data, size, "imu_t");
  in.skip(8 + 8);   // fingerprint, utime
  in.skipString();  // frame
  in.skip(48);      // angular_velocity, linear_acceleration
}

rgbd_frame_t encodeFrame(const RgbdFrame& frame, std::int64_t utime, const std::string& camera_id,
                         std::int64_t sequence, const FrameEncoding& encoding) {
  rgbd_frame_t message{};
  message.utime = utime;
  message.camera_id = camera_id;
  message.sequence = sequence;
  if (encoding.depth == kDepth32f) {
    message.depth = encodeDepth32f(frame.depth, utime);
  } else if (encoding.depth == kDepth16) {
    message.depth = encodeDepth16(frame.depth, encoding.depth_scale, utime);
  } else {
    throw InputError("unknown depth encoding '" + encoding.depth + "' (depth16 or depth32f)");
  }
  message.color = encodeColor(frame.color, utime);
  message.has_pose = encoding.with_pose;
  message.pose = encodePose(frame.T_W_C, utime);
  return message;
}

ReceivedFrame decodeFrame(const rgbd_frame_t& message) {
  ReceivedFrame received;
  received.utime = message.utime;
  received.camera_id = message.camera_id;
  received.sequence = message.sequence;
  received.frame = decodeImages(message);
  received.frame.timestamp_s = static_cast<double>(message.utime) * 1e-6;
  received.frame.name = "utime " + std::to_string(message.utime);
  received.has_pose = message.has_pose;
  if (message.has_pose) {
    if (message.pose.parent_frame != kWorldFrame) {
      throw InputError("frame pose is in '" + message.pose.parent_frame + "', expected '" +
                       std::string(kWorldFrame) + "' (T_W_C)");
    }
    received.frame.T_W_C = decodePose(message.pose);
    validatePose(received.frame.T_W_C, received.frame.name);
  }
  return received;
}

}  // namespace strata::lcm_io
