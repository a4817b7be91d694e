#pragma once
// stereo_image_t <-> grey stereo pairs, image_t "mono8" <-> GreyImage, imu_t <-> IMU samples, for
// visual-inertial input (strata-play sends EuRoC sessions this way). Decoding checks everything a
// sender can get wrong and throws InputError naming it: encodings, size fields that disagree with
// the payload, sizes over core/image_limits.h, a right image of another size than the left, time
// stamps that disagree, non-finite IMU values. Nothing is read past the payload.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "strata/core/types.h"
#include "strata/image_t.hpp"
#include "strata/imu_t.hpp"
#include "strata/stereo_image_t.hpp"

namespace strata::lcm_io {

/// GreyImage as image_t "mono8".
image_t encodeGrey(const GreyImage& grey, std::int64_t utime);
/// image_t "mono8" -> GreyImage; `what` ("left image") prefixes error messages.
GreyImage decodeGrey(const image_t& image, const std::string& what);

/// A decoded stereo_image_t. right is empty (and right_camera "") for mono.
struct StereoFrameMsg {
  std::int64_t utime = 0;
  std::int64_t sequence = 0;
  std::string left_camera;
  std::string right_camera;
  GreyImage left;
  GreyImage right;
};

/// Encodes a pair (right empty: mono, right_camera should then be "").
stereo_image_t encodeStereo(const GreyImage& left, const GreyImage& right, std::int64_t utime,
                            std::int64_t sequence, const std::string& left_camera,
                            const std::string& right_camera);
/// Checks and decodes. Refuses: a left image that is not mono8; a right image that is neither
/// mono8 of the left's size nor "" with no data; right_camera "" with a right image or named
/// without one; image utimes that differ from the message's; a negative sequence.
StereoFrameMsg decodeStereo(const stereo_image_t& message);

/// One IMU sample: gyro omega (rad/s) and specific force (m/s^2) in the IMU frame.
struct ImuMsg {
  std::int64_t utime = 0;
  std::string frame;
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

imu_t encodeImu(const ImuMsg& sample);
/// Refuses non-finite values.
ImuMsg decodeImu(const imu_t& message);

}  // namespace strata::lcm_io
