// LCM message types: every type round-trips through LCM (memq://, in-process), and the
// conversions between messages and Strata's types hold, including on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <vector>

#include "strata/core/error.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_image.h"
#include "strata/lcm/convert_pose.h"
#include "strata/change_event_t.hpp"
#include "strata/command_t.hpp"
#include "strata/esdf_slice_t.hpp"
#include "strata/imu_t.hpp"
#include "strata/keyframe_score_t.hpp"
#include "strata/map_stats_t.hpp"
#include "strata/mesh_update_t.hpp"

namespace strata::lcm_io {
namespace {

template <typename T>
std::vector<std::uint8_t> encoded(const T& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  EXPECT_EQ(message.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  return bytes;
}

void keepRaw(const lcm::ReceiveBuffer* buffer, const std::string&, std::vector<std::uint8_t>* out) {
  const auto* data = static_cast<const std::uint8_t*>(buffer->data);
  out->assign(data, data + buffer->data_size);
}

/// Publishes on memq://, receives, decodes; the decoded message re-encodes to the same bytes.
template <typename T>
T throughLcm(const T& message) {
  lcm::LCM lcm("memq://");
  EXPECT_TRUE(lcm.good());
  std::vector<std::uint8_t> received;
  lcm.subscribeFunction("ROUND_TRIP", &keepRaw, &received);
  EXPECT_EQ(lcm.publish("ROUND_TRIP", &message), 0);
  EXPECT_GT(lcm.handleTimeout(1000), 0);
  T decoded;
  decodePayload(received.data(), static_cast<int>(received.size()), decoded);
  EXPECT_EQ(encoded(decoded), encoded(message)) << T::getTypeName();
  return decoded;
}

RgbdFrame testFrame(int width, int height) {
  RgbdFrame frame;
  frame.depth = DepthImage(width, height);
  frame.color = ColorImage(width, height);
  for (int i = 0; i < width * height; ++i) {
    frame.depth.depth_m[i] = 0.5f + 0.0002f * static_cast<float>(i);
    frame.color.rgb[3 * i] = static_cast<std::uint8_t>(i);
    frame.color.rgb[3 * i + 2] = static_cast<std::uint8_t>(255 - i % 256);
  }
  frame.T_W_C = Eigen::Translation3d(1.0, -2.0, 0.5) *
                Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  return frame;
}

TEST(LcmTypes, FramePoseAndCameraInfoRoundTripExactly) {
  const RgbdFrame frame = testFrame(8, 6);
  FrameEncoding encoding;
  encoding.depth = kDepth32f;
  const rgbd_frame_t message = throughLcm(encodeFrame(frame, 1234567, "depth", 7, encoding));
  const ReceivedFrame received = decodeFrame(message);
  EXPECT_EQ(received.utime, 1234567);
  EXPECT_EQ(received.camera_id, "depth");
  EXPECT_EQ(received.sequence, 7);
  EXPECT_EQ(received.frame.depth.depth_m, frame.depth.depth_m);
  EXPECT_EQ(received.frame.color.rgb, frame.color.rgb);
  ASSERT_TRUE(received.has_pose);
  EXPECT_TRUE(received.frame.T_W_C.isApprox(frame.T_W_C, 1e-12));
  // What fusion uses (float) is bit-identical, so a map fused over LCM equals one fused directly.
  EXPECT_EQ(received.frame.T_W_C.matrix().cast<float>(), frame.T_W_C.matrix().cast<float>());

  CameraIntrinsics k;
  k.width_px = 8;
  k.height_px = 6;
  k.fx_px = 7.5f;
  const CameraIntrinsics back = decodeCameraInfo(throughLcm(encodeCameraInfo(k, "depth", 5)));
  EXPECT_EQ(back.width_px, 8);
  EXPECT_EQ(back.fx_px, 7.5f);
  EXPECT_EQ(back.cy_px, k.cy_px);
}

TEST(LcmTypes, OutputAndCommandTypesRoundTrip) {
  mesh_update_t mesh{};
  mesh.utime = 1;
  mesh.full = true;
  mesh.voxel_size_m = 0.05f;
  mesh_block_t block{};
  block.index[0] = -3;
  block.vertices = {{0.f, 1.f, 2.f}, {3.f, 4.f, 5.f}, {6.f, 7.f, 8.f}};
  block.colors = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  block.triangles = {{0, 1, 2}};
  block.num_vertices = 3;
  block.num_triangles = 1;
  mesh.blocks = {block};
  mesh.num_blocks = 1;
  const mesh_update_t mesh_back = throughLcm(mesh);
  ASSERT_EQ(mesh_back.blocks.size(), 1u);
  EXPECT_EQ(mesh_back.blocks[0].index[0], -3);
  EXPECT_EQ(mesh_back.blocks[0].vertices[2][1], 7.f);

  esdf_slice_t slice{};
  slice.width = 2;
  slice.height = 1;
  slice.distance_m = {{0.25f, std::nanf("")}};
  slice.state = {{2, 1}};
  EXPECT_TRUE(std::isnan(throughLcm(slice).distance_m[0][1]));

  map_stats_t stats{};
  stats.frames_fused = 12;
  stats.bad_channel = {"STRATA_RGBD"};
  stats.bad_count = {3};
  stats.num_channels = 1;
  stats.last_command_result = "ok";
  EXPECT_EQ(throughLcm(stats).bad_count[0], 3);

  change_event_t event{};
  event.object_id = 2;
  event.centroid[1] = 1.5f;
  event.vertices = {{1.f, 2.f, 3.f}};
  event.num_vertices = 1;
  EXPECT_EQ(throughLcm(event).centroid[1], 1.5f);

  keyframe_score_t score{};
  score.coverage = 0.4f;
  score.selected = true;
  score.reason = "low coverage";
  EXPECT_EQ(throughLcm(score).reason, "low coverage");

  command_t command{};
  command.command = command_t::SAVE_MAP;
  command.argument = "/tmp/x.strata";
  EXPECT_EQ(throughLcm(command).argument, "/tmp/x.strata");

  imu_t imu{};
  imu.frame = "imu";
  imu.linear_acceleration[2] = 9.81;
  EXPECT_EQ(throughLcm(imu).linear_acceleration[2], 9.81);
}

TEST(LcmTypes, ImageEncodingsDecodeToMetresAndRgb) {
  DepthImage depth(3, 1);
  depth.depth_m = {0.0f, 1.0f, 2.5002f};
  const DepthImage d16 = decodeDepth(encodeDepth16(depth, 5000.0f, 0));
  EXPECT_EQ(d16.depth_m[0], 0.0f);
  EXPECT_EQ(d16.depth_m[1], 1.0f);
  EXPECT_NEAR(d16.depth_m[2], 2.5002f, 1.0f / 5000.0f);

  image_t bgr{};
  bgr.encoding = kBgr8;
  bgr.width = 1;
  bgr.height = 1;
  bgr.data = {10, 20, 30};
  bgr.size = 3;
  EXPECT_EQ(decodeColor(bgr).rgb, (std::vector<std::uint8_t>{30, 20, 10}));
  image_t mono = bgr;
  mono.encoding = kMono8;
  mono.data = {77};
  mono.size = 1;
  EXPECT_EQ(decodeColor(mono).rgb, (std::vector<std::uint8_t>{77, 77, 77}));
}

TEST(LcmTypes, BadImagesAndPosesAreInputErrorsNamingTheProblem) {
  image_t image = encodeDepth32f(DepthImage(4, 4, 1.0f), 0);
  image.encoding = "depth64";
  EXPECT_THROW(decodeDepth(image), InputError);
  image.encoding = kDepth32f;
  image.data.pop_back();  // payload disagrees with width * height * 4
  try {
    decodeDepth(image);
    FAIL() << "a short payload must not decode";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected 64"), std::string::npos) << e.what();
  }
  image_t depth16 = encodeDepth16(DepthImage(2, 2, 1.0f), 0.0f, 0);
  EXPECT_THROW(decodeDepth(depth16), InputError);  // depth_scale 0

  pose_t pose = encodePose(Eigen::Isometry3d::Identity(), 0);
  pose.position[1] = std::nan("");
  EXPECT_THROW(decodePose(pose), InputError);
  pose = encodePose(Eigen::Isometry3d::Identity(), 0);
  pose.orientation[0] = 2.0;
  EXPECT_THROW(decodePose(pose), InputError);

  camera_info_t info = encodeCameraInfo(CameraIntrinsics{}, "depth", 0);
  info.distortion_model = "fisheye";
  EXPECT_THROW(decodeCameraInfo(info), InputError);
  info = encodeCameraInfo(CameraIntrinsics{}, "depth", 0);
  info.fx = 0.0;
  EXPECT_THROW(decodeCameraInfo(info), InputError);
}

TEST(LcmTypes, TruncatedAndLyingPayloadsNeverDecode) {
  const rgbd_frame_t message = encodeFrame(testFrame(16, 12), 99, "depth", 0, FrameEncoding{});
  const std::vector<std::uint8_t> bytes = encoded(message);
  for (std::size_t size = 0; size < bytes.size(); size += 7) {
    rgbd_frame_t decoded;
    EXPECT_THROW(decodePayload(bytes.data(), static_cast<int>(size), decoded), InputError)
        << "truncated to " << size << " bytes";
  }
  // A size field claiming 2^31 - 1 bytes is refused before the decoder allocates for it.
  rgbd_frame_t lying = message;
  std::vector<std::uint8_t> patched = encoded(lying);
  const std::size_t size_field = 8 + 8 + 4 + 6 + 8 + 8 + 4 + 8 + 12;  // depth image's size
  ASSERT_EQ(patched[size_field + 3], message.depth.size & 0xFF);
  patched[size_field] = 0x7F;
  patched[size_field + 1] = patched[size_field + 2] = patched[size_field + 3] = 0xFF;
  rgbd_frame_t decoded;
  EXPECT_THROW(decodePayload(patched.data(), static_cast<int>(patched.size()), decoded),
               InputError);
  pose_t pose;  // another type's payload: fingerprint mismatch
  EXPECT_THROW(decodePayload(bytes.data(), static_cast<int>(bytes.size()), pose), InputError);
}

}  // namespace
}  // namespace strata::lcm_io
