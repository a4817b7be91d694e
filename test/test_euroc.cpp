// EuRoC/ASL reader (io/euroc_dataset.h): the real V1_01_easy excerpt, and bad input written to
// temporary folders with the EuRoC writer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "strata/core/error.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/euroc_parse.h"
#include "strata/io/euroc_writer.h"
#include "strata/io/image_io.h"
#include "test_utils.h"

namespace strata::euroc {
namespace {

namespace fs = std::filesystem;

TEST(EurocMicro, ReadsCalibrationFramesImuAndTruth) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  const EurocDataset d = EurocDataset::open(folder);
  ASSERT_TRUE(d.stereo());
  const CameraCalibration& cam0 = d.calibration().cameras[0];
  const CameraCalibration& cam1 = d.calibration().cameras[1];
  EXPECT_EQ(cam0.width_px, 752);
  EXPECT_EQ(cam0.height_px, 480);
  EXPECT_DOUBLE_EQ(cam0.fu_px, 458.654);
  EXPECT_DOUBLE_EQ(cam0.fv_px, 457.296);
  EXPECT_DOUBLE_EQ(cam0.cu_px, 367.215);
  EXPECT_DOUBLE_EQ(cam0.cv_px, 248.375);
  EXPECT_EQ(cam0.distortion, DistortionModel::kRadialTangential);
  EXPECT_DOUBLE_EQ(cam0.distortion_coefficients[0], -0.28340811);
  EXPECT_DOUBLE_EQ(cam0.rate_hz, 20.0);
  EXPECT_NEAR(cam0.T_B_C(0, 1), -0.999880929698, 1e-9);
  EXPECT_NEAR(cam0.T_B_C(1, 3), -0.064676986768, 1e-12);
  // EuRoC's stereo baseline is about 11 cm, mostly along the left camera's x axis.
  const Eigen::Vector3d baseline = d.calibration().T_C0_C1().translation();
  EXPECT_NEAR(baseline.norm(), 0.110, 0.002);
  EXPECT_GT(baseline.x(), 0.109);
  EXPECT_EQ(cam1.name, "cam1");

  EXPECT_EQ(d.frames().size(), 95u);
  EXPECT_EQ(d.stats().left_frames, 95u);
  EXPECT_EQ(d.stats().right_frames, 95u);  // cam1/data.csv lists 99: 4 images left out
  EXPECT_EQ(d.stats().missing_images, 4u);
  EXPECT_NE(d.stats().first_missing_image.find("cam1/data/1403715278012143104.png"),
            std::string::npos);
  EXPECT_EQ(d.stats().unpaired_right, 0u);
  EXPECT_EQ(d.stats().unpaired_left, 0u);
  EXPECT_EQ(d.frames().front().timestamp_ns, 1403715273262142976);
  for (std::size_t i = 1; i < d.frames().size(); ++i) {
    EXPECT_NEAR(d.frames()[i].timestamp_ns - d.frames()[i - 1].timestamp_ns, 50e6,
                1000);  // 128 ns jitter
  }

  EXPECT_DOUBLE_EQ(d.calibration().imu.rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(d.calibration().imu.gyro_noise_density, 1.6968e-04);
  EXPECT_DOUBLE_EQ(d.calibration().imu.accel_random_walk, 3.0e-3);
  EXPECT_EQ(d.imu().size(), 1041u);
  EXPECT_EQ(d.stats().imu_nonfinite_skipped, 0u);
  EXPECT_EQ(d.stats().imu_gaps, 0u);
  const double span_s = (d.imu().back().timestamp_ns - d.imu().front().timestamp_ns) * 1e-9;
  EXPECT_NEAR((d.imu().size() - 1) / span_s, 200.0, 0.5);
  // Standing still: the accelerometer reads gravity, the gyro about nothing.
  EXPECT_NEAR(d.imu().front().accel_mps2.norm(), 9.81, 0.2);
  EXPECT_LT(d.imu().front().gyro_rad_s.norm(), 0.1);

  EXPECT_EQ(d.groundTruth().size(), 105u);
  EXPECT_NE(d.groundTruthFile().find("groundtruth_body.txt"), std::string::npos);
  EXPECT_NEAR(d.groundTruth().front().T_W_B.translation().x(), 0.878895, 1e-9);
  EXPECT_FALSE(d.groundTruth().front().has_velocity_and_biases);

  const StereoImages images = d.loadImages(0);
  EXPECT_EQ(images.left.width_px, 752);
  EXPECT_EQ(images.right.height_px, 480);
  EXPECT_EQ(images.left.pixels.size(), 752u * 480u);
}

TEST(EurocMicro, GroundTruthInterpolatesAtFrameTimes) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  const EurocDataset d = EurocDataset::open(folder);
  const std::vector<GroundTruthState>& gt = d.groundTruth();
  // The excerpt's TUM truth is at 20 Hz with stamps rounded to 10 us: frames fall between states.
  std::size_t found = 0;
  for (const StereoFrame& f : d.frames())
    found += interpolateGroundTruth(gt, f.timestamp_ns).has_value();
  EXPECT_GE(found, d.frames().size() - 1);
  EXPECT_FALSE(interpolateGroundTruth(gt, gt.front().timestamp_ns - 1).has_value());
  EXPECT_FALSE(interpolateGroundTruth(gt, gt.back().timestamp_ns + 1).has_value());
  ASSERT_TRUE(interpolateGroundTruth(gt, gt[3].timestamp_ns).has_value());
  EXPECT_TRUE(interpolateGroundTruth(gt, gt[3].timestamp_ns)->isApprox(gt[3].T_W_B));
  const std::int64_t mid = (gt[3].timestamp_ns + gt[4].timestamp_ns) / 2;
  const std::optional<Eigen::Isometry3d> between = interpolateGroundTruth(gt, mid);
  ASSERT_TRUE(between.has_value());
  const Eigen::Isometry3d& T = *between;
  EXPECT_NEAR(
      (T.translation() - 0.5 * (gt[3].T_W_B.translation() + gt[4].T_W_B.translation())).norm(), 0.0,
      1e-6);
  EXPECT_FALSE(interpolateGroundTruth(gt, mid, 1000).has_value());  // 50 ms apart: over 1 us
}

TEST(EurocMicro, EventsAreTimeOrderedImuFirstAtTies) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  const EurocDataset d = EurocDataset::open(folder);
  const std::vector<Event> events = d.events();
  ASSERT_EQ(events.size(), d.imu().size() + d.frames().size());
  std::size_t frames = 0;
  for (std::size_t i = 1; i < events.size(); ++i) {
    ASSERT_LE(events[i - 1].timestamp_ns, events[i].timestamp_ns) << i;
    if (events[i - 1].timestamp_ns == events[i].timestamp_ns) {
      EXPECT_EQ(events[i - 1].kind, Event::Kind::kImu);  // the first IMU shares cam0's first stamp
    }
  }
  for (const Event& e : events) {
    if (e.kind == Event::Kind::kFrame) {
      EXPECT_EQ(e.index, frames++);
      EXPECT_EQ(e.timestamp_ns, d.frames()[e.index].timestamp_ns);
    } else {
      EXPECT_EQ(e.timestamp_ns, d.imu()[e.index].timestamp_ns);
    }
  }
  EXPECT_EQ(frames, d.frames().size());
}

TEST(EurocMicro, MonoWhenRightCameraIsNotUsed) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  ReaderOptions options;
  options.use_right_camera = false;
  const EurocDataset d = EurocDataset::open(folder + "/mav0", options);
  EXPECT_FALSE(d.stereo());
  EXPECT_EQ(d.frames().size(), 95u);
  EXPECT_TRUE(d.frames().front().right_path.empty());
  EXPECT_TRUE(d.loadImages(3).right.empty());
  EXPECT_EQ(d.groundTruth().size(), 105u);  // found beside mav0 when opened at mav0/
}

// ---------------------------------------------------------------- bad input in temp folders

Calibration smallCalibration(bool stereo) {
  Calibration c;
  CameraCalibration cam;
  cam.name = "cam0";
  cam.width_px = 16;
  cam.height_px = 12;
  cam.fu_px = cam.fv_px = 20.0;
  cam.cu_px = 7.5;
  cam.cv_px = 5.5;
  cam.rate_hz = 20.0;
  c.cameras.push_back(cam);
  if (stereo) {
    cam.name = "cam1";
    cam.T_B_C.translation() = Eigen::Vector3d(0.1, 0.0, 0.0);
    c.cameras.push_back(cam);
  }
  c.imu.rate_hz = 200.0;
  c.imu.gyro_noise_density = 1e-4;
  return c;
}

class EurocBadInput : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("strata_test_euroc_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    // 5 frames at 20 Hz, IMU at 200 Hz over the same 0.2 s.
    EurocWriter writer(dir_.string(), smallCalibration(true));
    for (int k = 0; k < 5; ++k) {
      writer.addFrame(1'000'000'000 + k * 50'000'000, GreyImage(16, 12, 100),
                      GreyImage(16, 12, 90));
    }
    std::vector<ImuSample> imu;
    for (int k = 0; k <= 40; ++k) {
      imu.push_back({1'000'000'000 + k * 5'000'000, {0.0, 0.0, 0.5}, {0.0, 0.0, 9.75}});
    }
    writer.finish(imu, {});
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path mav0() const { return dir_ / "mav0"; }
  static void replaceInFile(const fs::path& path, const std::string& from, const std::string& to) {
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from << " not in " << path;
    text.replace(at, from.size(), to);
    std::ofstream(path) << text;
  }
  /// open() throws InputError containing every one of `parts`.
  void expectError(const std::vector<std::string>& parts) const {
    try {
      EurocDataset::open(dir_.string());
      FAIL() << "no error; expected one naming " << parts.front();
    } catch (const InputError& e) {
      for (const std::string& part : parts)
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
};

TEST_F(EurocBadInput, CleanFolderReadsBack) {
  const EurocDataset d = EurocDataset::open(dir_.string());
  EXPECT_TRUE(d.stereo());
  EXPECT_EQ(d.frames().size(), 5u);
  EXPECT_EQ(d.imu().size(), 41u);
  EXPECT_EQ(d.stats().imu_gaps, 0u);
  EXPECT_TRUE(d.groundTruth().empty());
  EXPECT_EQ(d.loadImages(4).right.at(3, 3), 90);
  EXPECT_NEAR(d.calibration().T_C0_C1().translation().x(), 0.1, 1e-15);
}

TEST_F(EurocBadInput, MissingFilesAreNamed) {
  fs::remove(mav0() / "imu0" / "data.csv");
  expectError({"imu0/data.csv", "not found"});
  fs::remove(mav0() / "cam0" / "sensor.yaml");
  expectError({"cam0/sensor.yaml", "not found"});
  EXPECT_THROW(EurocDataset::open((dir_ / "nowhere").string()), InputError);
}

TEST_F(EurocBadInput, MissingImagesAreCountedAndDropped) {
  fs::remove(mav0() / "cam1" / "data" / "1050000000.png");
  const EurocDataset d = EurocDataset::open(dir_.string());
  EXPECT_EQ(d.frames().size(), 4u);
  EXPECT_EQ(d.stats().missing_images, 1u);
  EXPECT_EQ(d.stats().unpaired_left, 1u);
  EXPECT_NE(d.stats().first_missing_image.find("cam1/data/1050000000.png"), std::string::npos);
  for (int k = 0; k < 5; ++k) {
    fs::remove(mav0() / "cam1" / "data" /
               (std::to_string(1'000'000'000 + k * 50'000'000) + ".png"));
  }
  expectError({"cam1/data.csv", "none of its 5 images"});
}

TEST_F(EurocBadInput, MissingFolders) {
  fs::remove_all(mav0() / "imu0");
  expectError({"imu0", "folder not found"});
  fs::remove_all(mav0() / "cam0" / "data");
  expectError({"cam0/data", "folder not found"});
}

TEST_F(EurocBadInput, ImageSizeNotOfTheResolutionIsNamed) {
  writeGreyPng((mav0() / "cam1" / "data" / "1000000000.png").string(), GreyImage(15, 12));
  expectError({"1000000000.png", "15x12", "16x12"});
  // A later frame is checked when loaded.
  writeGreyPng((mav0() / "cam1" / "data" / "1000000000.png").string(), GreyImage(16, 12));
  writeGreyPng((mav0() / "cam0" / "data" / "1100000000.png").string(), GreyImage(16, 13));
  const EurocDataset d = EurocDataset::open(dir_.string());
  try {
    d.loadImages(2);
    FAIL() << "no error for a 16x13 image";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1100000000.png: image is 16x13"), std::string::npos)
        << e.what();
  }
}

TEST_F(EurocBadInput, TimeGoingBackOrRepeatingNamesTheLine) {
  replaceInFile(mav0() / "imu0" / "data.csv", "1010000000,", "1005000000,");
  expectError({"imu0/data.csv:4:", "repeats"});
  replaceInFile(mav0() / "imu0" / "data.csv", "\n1005000000,0,0,0.5,0,0,9.75\n1005000000,",
                "\n1005000000,0,0,0.5,0,0,9.75\n1001000000,");
  expectError({"imu0/data.csv:4:", "goes back"});
}

TEST_F(EurocBadInput, NonFiniteImuIsSkippedAndGapsCounted) {
  replaceInFile(mav0() / "imu0" / "data.csv", "1010000000,0,0,0.5", "1010000000,nan,0,0.5");
  replaceInFile(mav0() / "imu0" / "data.csv", "1050000000,0,0,0.5,0,0,9.75",
                "1050000000,0,0,0.5,0,inf,9.75");
  // Remove two consecutive rows: one gap of 3 periods (2 samples missing).
  replaceInFile(mav0() / "imu0" / "data.csv", "1100000000,0,0,0.5,0,0,9.75\n", "");
  replaceInFile(mav0() / "imu0" / "data.csv", "1105000000,0,0,0.5,0,0,9.75\n", "");
  const EurocDataset d = EurocDataset::open(dir_.string());
  EXPECT_EQ(d.stats().imu_rows, 39u);
  EXPECT_EQ(d.stats().imu_nonfinite_skipped, 2u);
  EXPECT_EQ(d.imu().size(), 37u);
  EXPECT_EQ(d.stats().imu_gaps, 3u);             // the two skipped rows and the removed pair
  EXPECT_EQ(d.stats().imu_missing_samples, 4u);  // 1 + 1 + 2
  for (const ImuSample& s : d.imu())
    EXPECT_TRUE(s.gyro_rad_s.allFinite() && s.accel_mps2.allFinite());
}

TEST_F(EurocBadInput, UnmatchedStereoTimestampsAreCounted) {
  replaceInFile(mav0() / "cam1" / "data.csv", "1050000000,1050000000.png",
                "1055000000,1050000000.png");
  const EurocDataset d = EurocDataset::open(dir_.string());
  EXPECT_EQ(d.frames().size(), 4u);
  EXPECT_EQ(d.stats().unpaired_left, 1u);
  EXPECT_EQ(d.stats().unpaired_right, 1u);
  for (const StereoFrame& f : d.frames()) EXPECT_NE(f.timestamp_ns, 1'050'000'000);
}

TEST_F(EurocBadInput, CalibrationThatCannotFitTheImagesIsRefused) {
  const fs::path yaml = mav0() / "cam0" / "sensor.yaml";
  replaceInFile(yaml, "intrinsics: [20, 20, 7.5,", "intrinsics: [20, 20, 17.5,");
  expectError({"cam0/sensor.yaml", "principal point (17.5, 5.5) is outside the 16x12 image"});
  replaceInFile(yaml, "intrinsics: [20, 20, 17.5,", "intrinsics: [-20, 20, 7.5,");
  expectError({"cam0/sensor.yaml", "focal lengths"});
  replaceInFile(yaml, "intrinsics: [-20, 20, 7.5,", "intrinsics: [20, 20, 7.5,");
  replaceInFile(yaml, "data: [1, 0, 0, 0,", "data: [1.1, 0, 0, 0,");
  expectError({"cam0/sensor.yaml", "'T_BS' is not a rigid transform"});
  replaceInFile(yaml, "data: [1.1, 0, 0, 0,", "data: [-1, 0, 0, 0,");
  expectError({"cam0/sensor.yaml", "'T_BS' is not a rigid transform"});  // a reflection
  replaceInFile(yaml, "data: [-1, 0, 0, 0,", "data: [1, 0, 0, 0,");
  replaceInFile(yaml, "distortion_model: none", "distortion_model: fov");
  expectError({"cam0/sensor.yaml", "distortion_model 'fov'"});
}

TEST(EurocParse, AcceptsOpenCvHeaderAndRefusesMalformedRows) {
  const CameraCalibration c = parseCameraYaml(cameraYaml(smallCalibration(false).cameras[0]), "x");
  EXPECT_EQ(c.width_px, 16);
  EXPECT_EQ(c.distortion, DistortionModel::kNone);
  CameraCalibration fisheye = smallCalibration(false).cameras[0];
  fisheye.distortion = DistortionModel::kEquidistant;
  fisheye.distortion_coefficients = {0.1, -0.02, 0.003, -0.0004};
  const CameraCalibration f = parseCameraYaml(cameraYaml(fisheye), "x");
  EXPECT_EQ(f.distortion, DistortionModel::kEquidistant);
  EXPECT_DOUBLE_EQ(f.distortion_coefficients[3], -0.0004);
  std::string radtan = cameraYaml(fisheye);
  radtan.replace(radtan.find("equidistant"), 11, "radtan");
  EXPECT_EQ(parseCameraYaml(radtan, "x").distortion, DistortionModel::kRadialTangential);
  std::string none_with_values = cameraYaml(fisheye);
  none_with_values.replace(none_with_values.find("equidistant"), 11, "none");
  EXPECT_THROW(parseCameraYaml(none_with_values, "x"), InputError);  // coefficients need a model
  EXPECT_THROW(parseImageCsv("1,a.png\n1,b.png\n", "f.csv"), InputError);  // duplicate stamp
  EXPECT_THROW(parseImageCsv("1,a.png\n2,b.png,extra\n", "f.csv"), InputError);
  EXPECT_THROW(parseImageCsv("1,../a.png\n", "f.csv"), InputError);
  EXPECT_THROW(parseImageCsv("-5,a.png\n", "f.csv"), InputError);
  EXPECT_THROW(parseImuCsv("1,0,0,0,0,0,zero\n", "imu.csv"), InputError);
  const ImuCsv crlf = parseImuCsv("#header\r\n1,0,0,0,0,0,9.8\r\n\r\n2,0,0,0,0,0,9.8\r\n", "x");
  EXPECT_EQ(crlf.samples.size(), 2u);
  const std::vector<GroundTruthState> gt =
      parseGroundTruthCsv("5,1,2,3,1,0,0,0,0.5,0,0,0,0,0,0,0,0\n", "gt.csv");
  ASSERT_EQ(gt.size(), 1u);
  EXPECT_TRUE(gt[0].has_velocity_and_biases);
  EXPECT_DOUBLE_EQ(gt[0].velocity_W.x(), 0.5);
  EXPECT_THROW(parseGroundTruthCsv("5,1,2,3,0,0,0,0\n", "gt.csv"), InputError);  // zero quaternion
  EXPECT_THROW(parseGroundTruthTum("1.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n", "gt.txt"), InputError);
}

}  // namespace
}  // namespace strata::euroc
