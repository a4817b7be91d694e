// `strata select`: a map and a session folder in, keyframes.csv, selection.png and selected.png
// out; bad input gives a message naming the problem and a non-zero exit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include "cli/demo_command.h"
#include "cli/select_command.h"
#include "cli/select_outputs.h"
#include "cli/select_plot.h"
#include "fusion_fixture.h"
#include "strata/io/tum_writer.h"
#include "strata/map/map_file.h"
#include "strata/sim/analytic_dataset.h"

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
  // The session against its own extremes: the calibrated metrics select nothing. The surface
  // threshold is not calibrated (a share of the image): off here, checked below.
  o.calibrate_dir = o.session_dir;
  o.surface_threshold = -1.0;
  ASSERT_EQ(select(o), 0) << stderr_;
  EXPECT_NE(stdout_.find("0 of 8 keyframes"), std::string::npos) << stdout_;
  for (const char* file : {"keyframes.csv", "selection.png", "selected.png"}) {
    EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
  }
  std::ifstream csv(dir_ / "out" / "keyframes.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 1 + 8);
  // The last keyframe (source frame 15) looks past the map fused from frames 0-14: 6 % of its
  // measured samples fall where the map holds no surface, above the 2 % default: smoothed, it
  // lifts keyframes 5-7 over it, dilation adds 4; keyframes 0-3 stay near 1.2 %.
  o.surface_threshold = apps::SelectOptions{}.surface_threshold;
  ASSERT_EQ(select(o), 0) << stderr_;
  std::ifstream with_surface(dir_ / "out" / "keyframes.csv");
  std::vector<std::string> rows;
  for (std::string line; std::getline(with_surface, line);) rows.push_back(line);
  ASSERT_EQ(rows.size(), 1u + 8u);
  // ... similarity_smoothed, triggered, selected
  EXPECT_EQ(rows[8].substr(rows[8].size() - 12), ",0.00000,1,1") << rows[8];
  EXPECT_EQ(rows[1].substr(rows[1].size() - 12), ",0.00000,0,0") << rows[1];
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

// With the simulator's truth (strata demo --incremental), the CSV gains the true pixel shares and
// decision, and the plot a strip of truly positive keyframes under the selected ones.
TEST_F(SelectCliTest, TruthColumnsAndStrip) {
  constexpr std::size_t kKeyframes = 6;
  std::vector<selection::KeyframeScore> scores(kKeyframes);
  for (auto& k : scores) k.coverage = 1.0, k.ncc = k.histogram = 1.0;
  scores[2].coverage = 0.2;  // one keyframe looks into unmapped space
  selection::SelectionConfig config;
  config.smoothing_window = 1;
  config.dilation = 0;
  selection::TrajectorySelection s = selection::selectKeyframes(scores, config);
  ASSERT_EQ(s.selectedCount(), 1u);
  std::vector<apps::ScoredKeyframe> keyframes(kKeyframes);
  std::vector<selection::KeyframeTruth> truth(kKeyframes);
  for (std::size_t i = 0; i < kKeyframes; ++i) {
    keyframes[i].name = "k" + std::to_string(i);
    keyframes[i].score = scores[i];
    truth[i].valid_pixels = 100;
  }
  truth[2].unmapped_pixels = truth[2].positive_pixels = 80, truth[2].positive = true;
  truth[4].changed_pixels = truth[4].positive_pixels = 5, truth[4].positive = true;  // missed

  const fs::path csv = dir_ / "truth.csv";
  apps::writeSelectionCsv(csv.string(), keyframes, s, truth);
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_NE(header.find(",true_changed_fraction,true_unmapped_fraction,true_positive"),
            std::string::npos)
      << header;
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), kKeyframes);
  // ... triggered, selected, then the truth: selected and positive; missed and positive;
  // neither.
  EXPECT_EQ(rows[2].substr(rows[2].size() - 22), ",1,1,0.00000,0.80000,1") << rows[2];
  EXPECT_EQ(rows[4].substr(rows[4].size() - 22), ",0,0,0.05000,0.00000,1") << rows[4];
  EXPECT_EQ(rows[3].substr(rows[3].size() - 22), ",0,0,0.00000,0.00000,0") << rows[3];
  EXPECT_EQ(rows[0].back(), '0');
  truth.pop_back();
  EXPECT_THROW(apps::writeSelectionCsv(csv.string(), keyframes, s, truth), std::invalid_argument);

  std::vector<std::uint8_t> flags(kKeyframes, 0);
  flags[2] = flags[4] = 1;
  const ColorImage plain = apps::renderSelectionPlot(s, config);
  const ColorImage with_truth = apps::renderSelectionPlot(s, config, flags);
  EXPECT_GT(with_truth.height_px, plain.height_px);
  const auto count = [](const ColorImage& im, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    std::size_t n = 0;
    for (std::size_t p = 0; p + 2 < im.rgb.size(); p += 3) {
      n += im.rgb[p] == r && im.rgb[p + 1] == g && im.rgb[p + 2] == b;
    }
    return n;
  };
  EXPECT_EQ(count(plain, 70, 70, 190), 0u);
  EXPECT_GT(count(with_truth, 70, 70, 190), 0u);  // the two positive keyframes' cells
}

// A bad selection setting of `strata demo --incremental` ends it before any session is simulated.
TEST(SelectDemoOptions, BadWindowOrDilationExitsBeforeTheWork) {
  apps::DemoOptions o;
  o.incremental = true;
  o.quiet = true;
  o.out_dir =
      (fs::temp_directory_path() / ("strata_demo_bad_" + std::to_string(::getpid()))).string();
  for (const auto& [window, dilation, field] :
       {std::tuple{4, 0, "smoothing_window"}, std::tuple{1, -1, "dilation"}}) {
    o.select.smoothing_window = window;
    o.select.dilation = dilation;
    testing::internal::CaptureStderr();
    EXPECT_EQ(apps::runDemo(o), 2);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find(field), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(o.out_dir)) << "nothing written";
  }
}

}  // namespace
}  // namespace strata
