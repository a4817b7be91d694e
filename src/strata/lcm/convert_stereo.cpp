#include "strata/lcm/convert_stereo.h"

#include "strata/core/error.h"
#include "strata/core/image_limits.h"
#include "strata/lcm/convert_image.h"

namespace strata::lcm_io {

image_t encodeGrey(const GreyImage& grey, std::int64_t utime) {
  image_t image{};
  image.utime = utime;
  image.depth_scale = 0.0f;
  if (grey.empty()) return image;  // encoding "", size 0
  image.encoding = kMono8;
  image.width = grey.width_px;
  image.height = grey.height_px;
  image.data = grey.pixels;
  image.size = static_cast<std::int32_t>(image.data.size());
  return image;
}

GreyImage decodeGrey(const image_t& image, const std::string& what) {
  if (image.encoding != kMono8) {
    throw InputError(what + ": encoding '" + image.encoding + "' is not mono8");
  }
  checkImageSize(image.width, image.height, what);
  const std::size_t expected = static_cast<std::size_t>(image.width) * image.height;
  if (image.size < 0 || static_cast<std::size_t>(image.size) != expected ||
      image.data.size() != expected) {
    throw InputError(what + ": " + std::to_string(image.data.size()) +
                     " bytes of mono8 data (size " + std::to_string(image.size) + ") for " +
                     std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " pixels (expected " + std::to_string(expected) + ")");
  }
  GreyImage grey;
  grey.width_px = image.width;
  grey.height_px = image.height;
  grey.pixels = image.data;
  return grey;
}

stereo_image_t encodeStereo(const GreyImage& left, const GreyImage& right, std::int64_t utime,
                            std::int64_t sequence, const std::string& left_camera,
                            const std::string& right_camera) {
  stereo_image_t message{};
  message.utime = utime;
  message.sequence = sequence;
  message.left_camera = left_camera;
  message.right_camera = right.empty() ? "" : right_camera;
  message.left = encodeGrey(left, utime);
  message.right = encodeGrey(right, utime);
  return message;
}

StereoFrameMsg decodeStereo(const stereo_image_t& message) {
  if (message.sequence < 0) throw InputError("stereo frame: negative sequence");
  const std::string where = "stereo frame " + std::to_string(message.sequence);
  if (message.left.utime != message.utime) {
    throw InputError(where + ": left image utime " + std::to_string(message.left.utime) +
                     " differs from the frame's " + std::to_string(message.utime));
  }
  StereoFrameMsg frame;
  frame.utime = message.utime;
  frame.sequence = message.sequence;
  frame.left_camera = message.left_camera;
  frame.right_camera = message.right_camera;
  frame.left = decodeGrey(message.left, where + " left image");
  const bool mono = message.right.encoding.empty();
  if (mono) {
    if (message.right.size != 0 || !message.right.data.empty()) {
      throw InputError(where + ": right image has no encoding but " +
                       std::to_string(message.right.data.size()) + " bytes of data");
    }
    if (!message.right_camera.empty()) {
      throw InputError(where + ": right_camera '" + message.right_camera + "' without an image");
    }
    return frame;
  }
  if (message.right_camera.empty()) throw InputError(where + ": right image without right_camera");
  if (message.right.utime != message.utime) {
    throw InputError(where + ": right image utime " + std::to_string(message.right.utime) +
                     " differs from the frame's " + std::to_string(message.utime));
  }
  frame.right = decodeGrey(message.right, where + " right image");
  if (frame.right.width_px != frame.left.width_px ||
      frame.right.height_px != frame.left.height_px) {
    throw InputError(where + ": right image is " + std::to_string(frame.right.width_px) + "x" +
                     std::to_string(frame.right.height_px) + ", left is " +
                     std::to_string(frame.left.width_px) + "x" +
                     std::to_string(frame.left.height_px));
  }
  return frame;
}

imu_t encodeImu(const ImuMsg& sample) {
  imu_t message{};
  message.utime = sample.utime;
  message.frame = sample.frame;
  for (int a = 0; a < 3; ++a) {
    message.angular_velocity[a] = sample.gyro_rad_s[a];
    message.linear_acceleration[a] = sample.accel_mps2[a];
  }
  return message;
}

ImuMsg decodeImu(const imu_t& message) {
  ImuMsg sample;
  sample.utime = message.utime;
  sample.frame = message.frame;
  for (int a = 0; a < 3; ++a) {
    sample.gyro_rad_s[a] = message.angular_velocity[a];
    sample.accel_mps2[a] = message.linear_acceleration[a];
  }
  if (!sample.gyro_rad_s.allFinite() || !sample.accel_mps2.allFinite()) {
    throw InputError("imu sample at utime " + std::to_string(message.utime) +
                     ": non-finite angular_velocity or linear_acceleration");
  }
  return sample;
}

}  // namespace strata::lcm_io
