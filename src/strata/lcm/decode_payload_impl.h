#pragma once
// decodePayload (declared in convert_frame.h).
#include <exception>
#include <string>
#include <type_traits>

#include "strata/core/error.h"
#include "strata/camera_info_t.hpp"
#include "strata/command_t.hpp"
#include "strata/imu_t.hpp"
#include "strata/pose_t.hpp"
#include "strata/rgbd_frame_t.hpp"
#include "strata/stereo_image_t.hpp"

namespace strata::lcm_io {

template <typename Message>
void decodePayload(const void* data, int size, Message& message) {
  const std::string type = Message::getTypeName();
  if (data == nullptr || size < 8) {
    throw InputError(type + ": payload of " + std::to_string(size) + " bytes is too short");
  }
  if (size > kMaxPayloadBytes) {
    throw InputError(type + ": payload of " + std::to_string(size) + " bytes is over " +
                     "kMaxPayloadBytes = " + std::to_string(kMaxPayloadBytes));
  }
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  if constexpr (std::is_same_v<Message, rgbd_frame_t>) checkRgbdFrameLengths(bytes, size);
  if constexpr (std::is_same_v<Message, camera_info_t>) checkCameraInfoLengths(bytes, size);
  if constexpr (std::is_same_v<Message, pose_t>) checkPoseLengths(bytes, size);
  if constexpr (std::is_same_v<Message, command_t>) checkCommandLengths(bytes, size);
  if constexpr (std::is_same_v<Message, stereo_image_t>) checkStereoImageLengths(bytes, size);
  if constexpr (std::is_same_v<Message, imu_t>) checkImuLengths(bytes, size);
  int used = -1;
  try {
    used = message.decode(data, 0, size);
  } catch (const std::exception& e) {
    // NOTE: lcm-gen's decoders throw (length_error, bad_alloc) on some negative length fields.
    throw InputError(type + ": undecodable payload (" + e.what() + ")");
  }
  if (used < 0) {
    throw InputError(type + ": payload of " + std::to_string(size) +
                     " bytes does not decode (wrong type or truncated)");
  }
  if (used != size) {
    throw InputError(type + ": " + std::to_string(size - used) + " bytes left over after decoding");
  }
}

}  // namespace strata::lcm_io
