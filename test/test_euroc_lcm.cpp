// Grey stereo over LCM: the stereo_image_t codec refuses corrupt messages; strata-play's EuRoC
// playback on memq:// decodes back to the very images and IMU samples the reader gives.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <lcm/lcm-cpp.hpp>

#include "strata/core/error.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/euroc_writer.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_stereo.h"
#include "player/play_euroc.h"
#include "test_utils.h"

namespace strata::lcm_io {
namespace {

GreyImage ramp(int width, int height, int phase) {
  GreyImage image(width, height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = static_cast<std::uint8_t>((i * 7 + phase) & 0xFF);
  }
  return image;
}

/// decodeStereo throws InputError containing `part`.
void expectRefused(const stereo_image_t& message, const std::string& part) {
  try {
    decodeStereo(message);
    ADD_FAILURE() << "accepted; expected an error naming '" << part << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(LcmStereo, RoundTripThroughBytesAndMono) {
  const stereo_image_t message =
      encodeStereo(ramp(8, 6, 0), ramp(8, 6, 3), 1234, 5, "cam0", "cam1");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  ASSERT_EQ(message.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  stereo_image_t received;
  decodePayload(bytes.data(), static_cast<int>(bytes.size()), received);
  const StereoFrameMsg frame = decodeStereo(received);
  EXPECT_EQ(frame.utime, 1234);
  EXPECT_EQ(frame.sequence, 5);
  EXPECT_EQ(frame.right_camera, "cam1");
  EXPECT_EQ(frame.left.pixels, ramp(8, 6, 0).pixels);
  EXPECT_EQ(frame.right.pixels, ramp(8, 6, 3).pixels);
  // Truncated, or a length field claiming more than follows: refused before lcm-gen's decoder.
  EXPECT_THROW(decodePayload(bytes.data(), static_cast<int>(bytes.size()) - 10, received),
               InputError);
  std::vector<std::uint8_t> forged = bytes;
  forged[8 + 8 + 8 + 4 + 5 + 4 + 5 + 8 + 4 + 6 + 12] = 0x7F;  // left image's data length
  EXPECT_THROW(decodePayload(forged.data(), static_cast<int>(forged.size()), received), InputError);

  const StereoFrameMsg mono = decodeStereo(encodeStereo(ramp(8, 6, 1), {}, 7, 0, "cam0", "cam1"));
  EXPECT_TRUE(mono.right.empty());
  EXPECT_EQ(mono.right_camera, "");
}

TEST(LcmStereo, CorruptMessagesAreRefusedByName) {
  const stereo_image_t good = encodeStereo(ramp(8, 6, 0), ramp(8, 6, 3), 1234, 5, "cam0", "cam1");
  stereo_image_t m = good;
  m.left.encoding = "rgb8";
  expectRefused(m, "left image: encoding 'rgb8' is not mono8");
  m = good;
  m.right.data.pop_back();
  expectRefused(m, "right image: 47 bytes of mono8 data");
  m = good;
  m.left.size = 40;
  expectRefused(m, "left image: 48 bytes of mono8 data (size 40)");
  m = good;
  m.right = encodeGrey(ramp(6, 8, 0), 1234);
  expectRefused(m, "right image is 6x8, left is 8x6");
  m = good;
  m.right.utime = 1235;
  expectRefused(m, "right image utime 1235 differs");
  m = good;
  m.left.width = 100000;
  expectRefused(m, "left image");
  m = good;
  m.right_camera = "";
  expectRefused(m, "right image without right_camera");
  m = good;
  m.right.encoding = "";
  expectRefused(m, "right image has no encoding but 48 bytes");
  m = good;
  m.sequence = -1;
  expectRefused(m, "negative sequence");

  imu_t imu = encodeImu({1, "imu0", {0, 0, 1}, {0, 0, 9.8}});
  EXPECT_EQ(decodeImu(imu).accel_mps2.z(), 9.8);
  imu.linear_acceleration[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(decodeImu(imu), InputError);
}

/// What a subscriber saw, in arrival order.
struct Received {
  std::vector<StereoFrameMsg> frames;
  std::vector<ImuMsg> imu;
  std::vector<std::pair<std::int64_t, bool>> order;  // (utime, is_frame)
  // Raw handlers + decodePayload, as a consumer of outside data should (length fields checked).
  void onStereo(const lcm::ReceiveBuffer* buffer, const std::string&) {
    stereo_image_t m;
    decodePayload(buffer->data, static_cast<int>(buffer->data_size), m);
    frames.push_back(decodeStereo(m));
    order.emplace_back(m.utime, true);
  }
  void onImu(const lcm::ReceiveBuffer* buffer, const std::string&) {
    imu_t m;
    decodePayload(buffer->data, static_cast<int>(buffer->data_size), m);
    imu.push_back(decodeImu(m));
    order.emplace_back(m.utime, false);
  }
};

Received play(const apps::PlayOptions& options) {
  lcm::LCM lcm("memq://");
  EXPECT_TRUE(lcm.good());
  Received received;
  lcm.subscribe(kStereoChannel, &Received::onStereo, &received);
  lcm.subscribe(kImuChannel, &Received::onImu, &received);
  apps::playEuroc(options, lcm);
  while (lcm.handleTimeout(0) > 0) {
  }
  return received;
}

TEST(LcmStereo, EurocPlaybackDecodesToTheRecording) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  const euroc::EurocDataset d = euroc::EurocDataset::open(folder);
  apps::PlayOptions options;
  options.dataset = folder;
  options.rate = 0.0;  // as fast as possible
  options.restamp = false;
  options.quiet = true;
  const Received r = play(options);
  ASSERT_EQ(r.frames.size(), d.frames().size());
  ASSERT_EQ(r.imu.size(), d.imu().size());
  for (std::size_t i = 1; i < r.order.size(); ++i) {
    ASSERT_LE(r.order[i - 1].first, r.order[i].first) << "out of time order at message " << i;
  }
  for (std::size_t i = 0; i < r.frames.size(); i += 7) {
    const euroc::StereoImages images = d.loadImages(i);
    EXPECT_EQ(r.frames[i].utime, d.frames()[i].timestamp_ns / 1000);
    EXPECT_EQ(r.frames[i].sequence, static_cast<std::int64_t>(i));
    EXPECT_EQ(r.frames[i].left_camera, "cam0");
    EXPECT_EQ(r.frames[i].right_camera, "cam1");
    EXPECT_EQ(r.frames[i].left.pixels, images.left.pixels) << i;
    EXPECT_EQ(r.frames[i].right.pixels, images.right.pixels) << i;
  }
  for (std::size_t i = 0; i < r.imu.size(); ++i) {
    EXPECT_EQ(r.imu[i].utime, d.imu()[i].timestamp_ns / 1000);
    EXPECT_EQ(r.imu[i].gyro_rad_s, d.imu()[i].gyro_rad_s);  // bit-exact doubles
    EXPECT_EQ(r.imu[i].accel_mps2, d.imu()[i].accel_mps2);
  }
}

TEST(LcmStereo, EurocPlaybackPicksFramesAndTheImuBetweenThem) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  apps::PlayOptions options;
  options.dataset = folder;
  options.rate = 0.0;
  options.quiet = true;
  options.first = 10;
  options.frames = 5;
  options.stride = 2;  // frames 10, 12, ..., 18: 0.4 s
  const Received r = play(options);
  ASSERT_EQ(r.frames.size(), 5u);
  EXPECT_EQ(r.imu.size(), 81u);              // 0.4 s at 200 Hz, both ends
  EXPECT_EQ(r.order.front().second, false);  // the sample at the first frame's time comes first
  EXPECT_EQ(r.order.back().second, true);
  EXPECT_NEAR(static_cast<double>(r.frames.back().utime - r.frames.front().utime), 400000.0, 2.0);
}

TEST(LcmStereo, MonoSessionPlaysWithoutRightImages) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("strata_test_euroc_mono_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  euroc::Calibration calibration;
  euroc::CameraCalibration cam;
  cam.name = "cam0";
  cam.width_px = 12;
  cam.height_px = 10;
  cam.fu_px = cam.fv_px = 10.0;
  cam.cu_px = 5.5;
  cam.cv_px = 4.5;
  cam.rate_hz = 20.0;
  calibration.cameras.push_back(cam);
  calibration.imu.rate_hz = 200.0;
  euroc::EurocWriter writer(dir.string(), calibration);
  std::vector<euroc::ImuSample> imu;
  for (int k = 0; k < 3; ++k) writer.addFrame(k * 50'000'000, ramp(12, 10, k));
  for (int k = 0; k <= 20; ++k) imu.push_back({k * 5'000'000, {0, 0, 0.1 * k}, {0, 0, 9.8}});
  writer.finish(imu, {});
  apps::PlayOptions options;
  options.dataset = (dir / "mav0").string();
  options.rate = 0.0;
  options.restamp = false;
  options.quiet = true;
  const Received r = play(options);
  fs::remove_all(dir);
  ASSERT_EQ(r.frames.size(), 3u);
  ASSERT_EQ(r.imu.size(), 21u);
  EXPECT_TRUE(r.frames[2].right.empty());
  EXPECT_EQ(r.frames[2].right_camera, "");
  EXPECT_EQ(r.frames[2].left.pixels, ramp(12, 10, 2).pixels);
  EXPECT_EQ(r.frames[2].utime, 100'000);
  EXPECT_EQ(r.imu[20].gyro_rad_s.z(), 0.1 * 20);
}

}  // namespace
}  // namespace strata::lcm_io
