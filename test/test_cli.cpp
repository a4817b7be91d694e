// `strata fuse` on bad input: a clear error naming the problem, a non-zero exit, and nothing that
// was fused before the bad frame is lost (the map file holds it). A map that cannot be saved (full
// disk, read-only folder) leaves the previous file at the path as it was, and the error says so.
#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>

#include "cli/fuse_command.h"
#include "strata/core/atomic_file.h"
#include "strata/core/file_faults.h"
#include "strata/io/image_io.h"
#include "strata/io/tum_writer.h"
#include "strata/map/map_file.h"
#include "strata/sim/analytic_dataset.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

class FuseCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("strata_cli_" + std::string(::testing::UnitTest::GetInstance()
                                            ->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    sim::AnalyticDatasetConfig config;
    config.frame_count = 4;
    config.render_color = false;
    const sim::AnalyticDataset source(config);
    for (std::size_t i = 0; i < source.size(); ++i) frames_.push_back(source.load(i));
    intrinsics_ = source.intrinsics();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string writeDataset(const std::string& name) {
    const std::string path = (dir_ / name).string();
    writeTumDataset(path, intrinsics_, frames_);
    return path;
  }

  int fuse(const std::string& dataset, const std::string& map_name = "map.strata", int frames = 0,
           bool skip_bad_frames = false) {
    apps::FuseOptions options;
    options.dataset = dataset;
    options.frames = frames;
    options.map_path = (dir_ / map_name).string();
    options.quiet = true;
    options.skip_bad_frames = skip_bad_frames;
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    const int code = apps::runFuse(options);
    stderr_ = testing::internal::GetCapturedStderr();
    stdout_ = testing::internal::GetCapturedStdout();
    return code;
  }

  fs::path dir_;
  std::vector<RgbdFrame> frames_;
  CameraIntrinsics intrinsics_;
  std::string stderr_;
  std::string stdout_;
};

TEST_F(FuseCliTest, GoodDatasetFusesAndExitsZero) {
  EXPECT_EQ(fuse(writeDataset("good")), 0) << stderr_;
  EXPECT_GT(loadMap((dir_ / "map.strata").string()).blockCount(), 100u);
}

TEST_F(FuseCliTest, MissingAndEmptyDatasetsAreRefused) {
  EXPECT_NE(fuse((dir_ / "does_not_exist").string()), 0);
  EXPECT_NE(stderr_.find("does_not_exist"), std::string::npos) << stderr_;
  fs::create_directories(dir_ / "empty");
  EXPECT_NE(fuse((dir_ / "empty").string()), 0);
  EXPECT_NE(stderr_.find("empty"), std::string::npos) << stderr_;
  EXPECT_FALSE(fs::exists(dir_ / "map.strata"));
}

TEST_F(FuseCliTest, ZeroIntrinsicsAreRefused) {
  const std::string path = writeDataset("zero_fx");
  std::ofstream(path + "/camera.yaml") << "width: 640\nheight: 480\nfx: 0\nfy: 525\ncx: 319.5\n"
                                       << "cy: 239.5\ndepth_scale: 5000\n";
  EXPECT_NE(fuse(path), 0);
  EXPECT_NE(stderr_.find("fx"), std::string::npos) << stderr_;
}

TEST_F(FuseCliTest, BadFrameMidwayStopsWithoutOutputOrIsSkippedWhenAsked) {
  const std::string path = writeDataset("bad_frame");
  // Frame 2's depth image is replaced by one of the wrong size.
  writeDepthPng(path + "/depth/000002.png", DepthImage(320, 240, 1.0f), 5000.0);
  EXPECT_EQ(fuse(path, "partial.strata"), 1);
  EXPECT_NE(stderr_.find("000002.png"), std::string::npos) << stderr_;
  EXPECT_NE(stderr_.find("no output written"), std::string::npos) << stderr_;
  EXPECT_NE(stderr_.find("--skip-bad-frames"), std::string::npos) << stderr_;
  EXPECT_FALSE(fs::exists(dir_ / "partial.strata")) << "a map of part of the frames";

  // With --skip-bad-frames the other frames are fused: the map of the dataset without frame 2.
  EXPECT_EQ(fuse(path, "skipped.strata", 0, true), 0) << stderr_;
  EXPECT_NE(stdout_.find("Skipped 1 bad frame"), std::string::npos) << stdout_;
  EXPECT_NE(stderr_.find("skipped frame 3 of 4"), std::string::npos) << stderr_;
  std::vector<RgbdFrame> without = frames_;
  without.erase(without.begin() + 2);
  const std::string three = (dir_ / "three_frames").string();
  writeTumDataset(three, intrinsics_, without);
  EXPECT_EQ(fuse(three, "three.strata"), 0) << stderr_;
  const TsdfMap skipped = loadMap((dir_ / "skipped.strata").string());
  EXPECT_GT(skipped.blockCount(), 100u);
  EXPECT_EQ(serializeMap(skipped), serializeMap(loadMap((dir_ / "three.strata").string())));
}

TEST_F(FuseCliTest, MissingFileAndNonFinitePoseAreRefused) {
  const std::string missing = writeDataset("missing_file");
  fs::remove(missing + "/depth/000001.png");
  EXPECT_NE(fuse(missing), 0);
  EXPECT_NE(stderr_.find("000001.png"), std::string::npos) << stderr_;

  const std::string nan_pose = writeDataset("nan_pose");
  std::ofstream(nan_pose + "/groundtruth.txt")
      << "# timestamp tx ty tz qx qy qz qw\n0.000000 nan 0 0 0 0 0 1\n";
  EXPECT_NE(fuse(nan_pose), 0);
  EXPECT_FALSE(stderr_.empty());
}

TEST_F(FuseCliTest, FailedSaveExitsNonZeroNamesThePathAndKeepsThePreviousMap) {
  const std::string dataset = writeDataset("good");
  const std::string map_path = (dir_ / "map.strata").string();
  ASSERT_EQ(fuse(dataset, "map.strata", 2), 0) << stderr_;
  const std::vector<std::uint8_t> previous = readFile(map_path);
  for (const auto& [step, error_number] :
       {std::pair{FileStep::kWrite, ENOSPC}, std::pair{FileStep::kOpen, EROFS}}) {
    const ScopedFileFault fault(step, error_number);
    EXPECT_NE(fuse(dataset), 0) << "all frames fused, but the map was not saved";
    EXPECT_NE(stderr_.find("'" + map_path + "'"), std::string::npos) << stderr_;
    EXPECT_NE(stderr_.find(std::strerror(error_number)), std::string::npos) << stderr_;
    EXPECT_NE(stderr_.find("still holds the map saved there before"), std::string::npos) << stderr_;
    EXPECT_EQ(readFile(map_path), previous) << "the previous map must survive byte for byte";
  }
  EXPECT_EQ(fuse(dataset), 0) << "and with the disk back, the new map is saved";
  EXPECT_NE(readFile(map_path), previous);
}

}  // namespace
}  // namespace strata
