// strata-mapper under bad input: 10,000 random, truncated and invalid messages on its input
// channels are counted per channel, never crash it and never change the map; a map or object
// database path it could not save to is refused at start, not after a session.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "lcm_test_helpers.h"
#include "test_utils.h"
#include "strata/camera_info_t.hpp"

namespace strata::test {
namespace {

namespace fs = std::filesystem;
using namespace lcm_io;

constexpr int kBadMessages = 10000;

CameraIntrinsics tinyCamera() {
  CameraIntrinsics k;
  k.width_px = 32;
  k.height_px = 24;
  k.fx_px = k.fy_px = 30.0f;
  k.cx_px = 15.5f;
  k.cy_px = 11.5f;
  return k;
}

/// A wall 1.5 m in front of the camera.
RgbdFrame wallFrame(double x_m) {
  RgbdFrame frame;
  frame.depth = DepthImage(32, 24, 1.5f);
  frame.T_W_C = Eigen::Translation3d(x_m, 0.0, 0.0) * Eigen::Isometry3d::Identity();
  return frame;
}

template <typename T>
std::vector<std::uint8_t> bytesOf(const T& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

/// Message `i` of the fuzz run: every one is bad in its own way. Returns its channel.
std::string badMessage(int i, std::int64_t last_utime, std::mt19937& rng,
                       std::vector<std::uint8_t>* bytes) {
  const std::vector<std::string> inputs = {kRgbdChannel, kPoseChannel, kCameraInfoChannel,
                                           kCommandChannel};
  FrameEncoding encoding;
  rgbd_frame_t frame = encodeFrame(wallFrame(0.0), last_utime + 1000 + i, "depth", i, encoding);
  switch (i % 9) {
    case 0: {  // random bytes on any input channel
      bytes->resize(std::uniform_int_distribution<int>(0, 3000)(rng));
      for (auto& b : *bytes) b = static_cast<std::uint8_t>(rng());
      return inputs[rng() % inputs.size()];
    }
    case 1: {  // a valid frame cut short
      *bytes = bytesOf(frame);
      bytes->resize(std::uniform_int_distribution<std::size_t>(0, bytes->size() - 1)(rng));
      return kRgbdChannel;
    }
    case 2:
      frame.depth.encoding = "depth64";
      break;  // unknown encoding
    case 3:
      frame.depth.width = 31;
      break;  // size disagrees with payload
    case 4:
      frame.pose.position[0] = std::nan("");
      break;  // NaN pose
    case 5:
      frame.utime = last_utime - 1;
      break;  // out-of-order stamp
    case 6: {
      pose_t pose = encodePose(wallFrame(0.0).T_W_C, last_utime + i);
      pose.orientation[rng() % 4] = std::nan("");
      *bytes = bytesOf(pose);
      return kPoseChannel;
    }
    case 7: {  // the right fingerprint, then garbage: length fields that lie
      const bool as_frame = rng() % 2 == 0;
      *bytes = as_frame ? bytesOf(frame) : bytesOf(encodeCameraInfo(tinyCamera(), "depth", 0));
      bytes->resize(8 + std::uniform_int_distribution<std::size_t>(0, 3000)(rng));
      for (std::size_t b = 8; b < bytes->size(); ++b)
        (*bytes)[b] = static_cast<std::uint8_t>(rng());
      return as_frame ? kRgbdChannel : kCameraInfoChannel;
    }
    default: {
      camera_info_t info = encodeCameraInfo(tinyCamera(), "depth", 0);
      info.width = -static_cast<int>(rng() % 1000);
      *bytes = bytesOf(info);
      return kCameraInfoChannel;
    }
  }
  *bytes = bytesOf(frame);
  return kRgbdChannel;
}

std::string saveAndRead(InProcessMapper& mapper, apps::FramePublisher& publisher,
                        const fs::path& path) {
  const std::int64_t id = publisher.command(command_t::SAVE_MAP, path.string());
  EXPECT_TRUE(InProcessMapper::waitFor(
      [&] { return mapper.outputs().latestStats().last_command_id == id; }));
  EXPECT_EQ(mapper.outputs().latestStats().last_command_result, "ok");
  const std::vector<std::uint8_t> bytes = readFile(path.string());
  return std::string(bytes.begin(), bytes.end());
}

TEST(LcmMapperFuzz, TenThousandBadMessagesAreCountedAndLeaveTheMapAlone) {
  const fs::path dir =
      fs::temp_directory_path() / ("strata_test_lcm_fuzz_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  InProcessMapper mapper(testMapperOptions());
  apps::FramePublisher publisher(mapper.lcm(), apps::PublisherChannels::defaults(), "depth",
                                 FrameEncoding{});
  const std::int64_t t0 = nowUtime();
  for (int i = 0; i < 3; ++i) publisher.publish(wallFrame(0.1 * i), tinyCamera(), t0 + 1000 * i);
  ASSERT_TRUE(
      InProcessMapper::waitFor([&] { return mapper.outputs().latestStats().frames_fused == 3; }));
  const std::string before = saveAndRead(mapper, publisher, dir / "before.strata");

  std::mt19937 rng(7);
  std::vector<std::uint8_t> bytes;
  for (int i = 0; i < kBadMessages; ++i) {
    const std::string channel = badMessage(i, t0 + 2000, rng, &bytes);
    ASSERT_EQ(mapper.lcm().publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())), 0);
  }
  ASSERT_TRUE(InProcessMapper::waitFor([&] {
    return mapper.node().counters().messages_bad >= kBadMessages;
  })) << "only "
      << mapper.node().counters().messages_bad << " bad messages counted";
  const std::string after = saveAndRead(mapper, publisher, dir / "after.strata");
  EXPECT_TRUE(before == after) << "bad messages changed the map";

  const map_stats_t stats = mapper.outputs().latestStats();
  EXPECT_EQ(stats.messages_bad, kBadMessages);
  EXPECT_EQ(stats.frames_fused, 3);
  std::int64_t per_channel = 0;
  for (std::int64_t count : stats.bad_count) per_channel += count;
  EXPECT_EQ(per_channel, kBadMessages);
  EXPECT_EQ(stats.num_channels, 4) << "bad messages on every input channel";

  // Still mapping: a good frame after the flood is fused.
  publisher.publish(wallFrame(0.5), tinyCamera(), t0 + 10000000);
  EXPECT_TRUE(
      InProcessMapper::waitFor([&] { return mapper.outputs().latestStats().frames_fused == 4; }));
  fs::remove_all(dir);
}

TEST(LcmMapperOptions, AMapPathItCannotSaveToIsRefusedAtStart) {
  const fs::path dir = freshTempDir("mapper_paths");
  apps::MapperOptions options = testMapperOptions();
  options.map_path = (dir / "no_such_folder" / "map.strata").string();
  try {
    options.validate();
    ADD_FAILURE() << "a map in a folder that does not exist was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--map"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  options.map_path = dir.string();  // a folder
  EXPECT_THROW(options.validate(), InputError);
  options.map_path = (dir / "map.strata").string();
  options.objects_path = options.map_path;  // both saves on one file
  EXPECT_THROW(options.validate(), InputError);
  options.objects_path.clear();
  EXPECT_NO_THROW(options.validate());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test
