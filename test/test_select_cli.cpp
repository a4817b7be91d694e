// `strata select`: a map and a session folder in, keyframes.csv, selection.png and selected.png
// out; bad input gives a message naming the problem and a non-zero exit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "apps/select_command.h"
#include "fusion_fixture.h"
#include "io/tum_writer.h"
#include "map/map_file.h"
#include "sim/analytic_dataset.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

class SelectCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("strata_select_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // The map from every other frame of the analytic room; the session is 8 of its frames.
    sim::AnalyticDatasetConfig config;
    config.frame_count = 16;
    const sim::AnalyticDataset source(config);
    MapConfig map_config;
    map_config.voxel_size_m = 0.05f;
    saveMap(test::fuseReference(source, map_config, 16, 2), (dir_ / "map.strata").string());
    std::vector<RgbdFrame> frames;
    for (std::size_t i = 1; i < 16; i += 2) frames.push_back(source.load(i));
    writeTumDataset((dir_ / "session").string(), source.intrinsics(), frames);
  }
  void TearDown() override { fs::remove_all(dir_); }

  int select(apps::SelectOptions options) {
    options.quiet = true;
    options.out_dir = (dir_ / "out").string();
    testing::internal::CaptureStderr();
    testing::internal::CaptureStdout();
    const int code = apps::runSelect(options);
    stdout_ = testing::internal::GetCapturedStdout();
    stderr_ = testing::internal::GetCapturedStderr();
    return code;
  }

  apps::SelectOptions goodOptions() const {
    apps::SelectOptions o;
    o.map_path = (dir_ / "map.strata").string();
    o.session_dir = (dir_ / "session").string();
    return o;
  }

  fs::path dir_;
  std::string stdout_, stderr_;
};

TEST_F(SelectCliTest, WritesCsvPlotAndContactSheet) {
  apps::SelectOptions o = goodOptions();
  o.calibrate_dir = o.session_dir;  // the session against its own map: nothing is new
  ASSERT_EQ(select(o), 0) << stderr_;
  EXPECT_NE(stdout_.find("0 of 8 keyframes"), std::string::npos) << stdout_;
  for (const char* file : {"keyframes.csv", "selection.png", "selected.png"}) {
    EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
  }
  std::ifstream csv(dir_ / "out" / "keyframes.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 1 + 8);
  // Coverage demanded beyond what the frames show selects them all.
  o.calibrate_dir.clear();
  o.coverage_threshold = 1.01;
  ASSERT_EQ(select(o), 0) << stderr_;
  EXPECT_NE(stdout_.find("8 of 8 keyframes"), std::string::npos) << stdout_;
}

TEST_F(SelectCliTest, BadInputExitsNonZeroNamingTheProblem) {
  apps::SelectOptions o = goodOptions();
  o.map_path = (dir_ / "missing.strata").string();
  EXPECT_EQ(select(o), 2);
  EXPECT_NE(stderr_.find("missing.strata"), std::string::npos) << stderr_;
  o = goodOptions();
  o.session_dir = (dir_ / "nowhere").string();
  EXPECT_EQ(select(o), 2);
  EXPECT_NE(stderr_.find("nowhere"), std::string::npos) << stderr_;
  o = goodOptions();
  o.method = "sift";
  EXPECT_EQ(select(o), 2);
  EXPECT_NE(stderr_.find("sift"), std::string::npos) << stderr_;
  o = goodOptions();
  o.window = 4;
  EXPECT_EQ(select(o), 2);
  EXPECT_NE(stderr_.find("smoothing_window"), std::string::npos) << stderr_;
  o = goodOptions();
  o.stride_px = 0;
  EXPECT_EQ(select(o), 2);
  EXPECT_NE(stderr_.find("stride"), std::string::npos) << stderr_;
}

}  // namespace
}  // namespace strata
