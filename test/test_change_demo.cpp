// Change detection end to end: the label overlay picture, `strata diff` on the command line, and
// the room against its ground truth, on the true poses and on poses from VIO (the CI runs; the
// full five sessions are in test_demo_long).
#include <gtest/gtest.h>

#include <filesystem>

#include "strata/change/object_discovery.h"
#include "change_test_scene.h"
#include "cli/demo_command.h"
#include "cli/demo_report.h"
#include "cli/diff_command.h"
#include "cli/diff_overlay.h"
#include "cli/sim_command.h"
#include "strata/core/error.h"
#include "demo_targets.h"
#include "strata/io/image_io.h"
#include "strata/mesh/ply.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

// Moved objects and arrivals the truth counts in the CI runs below (measured: 7 moved objects
// and 4 arrivals in two sessions, 7 moved objects in the two VIO sessions).
constexpr std::size_t kTwoSessionMoved = 6;
constexpr std::size_t kTwoSessionArrivals = 3;
constexpr std::size_t kShortVioMoved = 5;

std::array<std::uint8_t, 3> pixel(const ColorImage& image, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * image.width_px + x) * 3;
  return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

TEST(ChangeOverlay, ColoursObjectsSeenFromAbove) {
  const test::ObjectsScene scene = test::makeObjectsScene();
  change::LabelledSurface surface;
  const auto objects =
      change::extractObjects(scene.map, scene.labels, change::ObjectConfig{}, 1, nullptr, &surface);
  ASSERT_EQ(objects.size(), 2u);
  apps::OverlayOptions options;
  options.title = "SESSION 1";
  const ColorImage image = apps::renderOverlay(surface.mesh, objects, options);
  // 2 m at the 5 mm minimum pixel: the map is about 400 px wide, with title and legend around it.
  EXPECT_GT(image.width_px, 400);
  EXPECT_GT(image.height_px, 400);
  // Count pixels of the first two palette colours (objects 1 and 2), shaded by up to 0.55.
  int red = 0, blue = 0;
  for (int y = 0; y < image.height_px; ++y) {
    for (int x = 0; x < image.width_px; ++x) {
      const auto p = pixel(image, x, y);
      if (p[0] > 110 && p[1] < 45 && p[2] < 45) ++red;
      if (p[2] > 95 && p[0] < 35 && p[1] > 60 && p[1] < 125) ++blue;
    }
  }
  // Box A's top is 0.4 x 0.3 m = 4800 pixels of 5 mm, box B's 0.3 x 0.3 m = 3600 (plus legend).
  EXPECT_NEAR(red, 4800, 900);
  EXPECT_NEAR(blue, 3600, 800);
  if (const char* dir = std::getenv("STRATA_TEST_OUTPUT")) {
    writeColorPng((fs::path(dir) / "overlay.png").string(), image);
  }
  EXPECT_THROW(apps::renderOverlay(Mesh{}, {}, options), InputError);
}

/// A fresh folder under the temporary directory.
fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  return dir;
}

TEST(DiffCommand, MissingSessionFolderFailsNamingIt) {
  apps::DiffOptions options;
  const fs::path missing = freshDir("strata_diff_missing_session");
  options.sessions = {missing.string(), missing.string() + "_too"};
  options.out_dir = freshDir("strata_diff_missing_out").string();
  options.quiet = true;
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runDiff(options), 2);
  const std::string message = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(options.out_dir)) << "nothing is written before the inputs are checked";
}

TEST(DiffCommand, ComparesSimulatedSessionsAndWritesEveryOutput) {
  const fs::path sim = freshDir("strata_diff_sim");
  apps::SimOptions sim_options;
  sim_options.sessions = 2;
  sim_options.max_frames = 8;
  sim_options.out_dir = sim.string();
  sim_options.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runSim(sim_options), 0);
  testing::internal::GetCapturedStdout();
  apps::DiffOptions options;
  options.sessions = {(sim / "session_0").string(), (sim / "session_1").string()};
  options.out_dir = freshDir("strata_diff_out").string();
  options.voxel_size_m = 0.05f;  // fast; the room's objects still span several voxels
  options.min_weight = 2.0f;
  options.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runDiff(options), 0);
  const std::string summary = testing::internal::GetCapturedStdout();
  EXPECT_NE(summary.find("Compared 2 sessions"), std::string::npos) << summary;
  const fs::path out(options.out_dir);
  EXPECT_TRUE(fs::exists(out / "static_mesh.ply"));
  EXPECT_TRUE(fs::exists(out / "report.json"));
  for (const char* overlay : {"session_0_overlay.png", "session_1_overlay.png"}) {
    EXPECT_TRUE(fs::exists(out / overlay)) << overlay;
  }
  EXPECT_FALSE(readPly((out / "static_mesh.ply").string()).empty());
  fs::remove_all(sim);
  fs::remove_all(out);
}

// The demo's targets (demo_targets.h) on the first two of the room's five sessions, with keyframe
// selection (--incremental): the CI run of ChangeDemo.DefaultRoomMeetsItsTargets, which
// test_demo_long runs over all five sessions (about 4 min on 2 cores, labelled long; three
// sessions took 125 s, over CI's 2 minutes per test). Measured (50 s): precision 100 % (8/8),
// recall 100 % (7/7), 99.3 % of the static surface within 2 cm; the selected keyframes find 7 of
// 7 and 4 of 4 arrivals.
TEST(ChangeDemo, FirstTwoRoomSessionsMeetTheTargets) {
  apps::DemoOptions options = test::roomDemoOptions("strata_change_demo");
  options.objects = false;  // the object database step has its own test (test_objects_demo)
  options.incremental = true;
  options.sessions = 2;
  const apps::DemoReport report = apps::runDemoPipeline(options);
  test::expectRoomChangeTargets(report, kTwoSessionMoved, kTwoSessionArrivals);
  fs::remove_all(options.out_dir);
}

// The demo on poses from stereo VIO (`strata demo --vio`): two sessions of the room, 376 x 240
// grey stereo, each session's frames fused on the VIO's poses but those before tracking starts,
// and change detection still finds the moved objects. The CI run has 20 frames per session;
// test_demo_long runs 30 (ChangeDemo.VioPosesKeepChangeDetection, about 3 min on 2 cores).
// Measured (104 s beside another test): 24-31 mm RMSE, 42-56 mm at most, 0.9-1.1 deg, 1 frame
// skipped per session; change detection 7 of 7, precision 8 of 8.
TEST(ChangeDemo, VioPosesOfTwoShortSessionsKeepChangeDetection) {
  const apps::DemoOptions options = test::roomVioDemoOptions("strata_change_demo_vio", 20);
  const apps::DemoReport report = apps::runDemoPipeline(options);
  test::expectVioDemoTargets(report, 2, 20, kShortVioMoved);
  fs::remove_all(options.out_dir);
}

// Teach and repeat with no truth poses (`strata demo --localize`): session 0's drifting odometry
// is the map, session 1 in a drifting frame of its own is localised against it frame by frame.
// Measured (49 s): 58 of 60 frames localised, 59 placed, none wrong, largest error 101 mm against
// the truth, which holds the teach session's own drift (its odometry alone: 75 mm). Change
// detection is scored against the world's truth, which the teach map's drift moves away from
// (docs/localize.md), so it is not asserted here.
TEST(ChangeDemo, RepeatSessionLocalisesAgainstTheTeachSessionsMap) {
  apps::DemoOptions options = test::roomDemoOptions("strata_change_demo_localize");
  options.objects = false;
  options.sessions = 2;
  options.localize = true;
  const apps::DemoReport report = apps::runDemoPipeline(options);
  ASSERT_TRUE(report.localization);
  ASSERT_EQ(report.localization->sessions.size(), 1u);
  const apps::DemoLocalizeSession& s = report.localization->sessions[0];
  EXPECT_GE(s.localized * 10, s.attempted * 8);
  EXPECT_GE(s.placed * 10, s.frames * 9);
  EXPECT_EQ(s.wrong, 0u);
  EXPECT_LT(s.max_error_m, 0.15);
  fs::remove_all(options.out_dir);
}

}  // namespace
}  // namespace strata
