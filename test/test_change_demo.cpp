// Change detection end to end: the label overlay picture, `strata diff` on the command line, and
// the default 5-session room against its ground truth, on the true poses and on poses from VIO.
#include <gtest/gtest.h>

#include <filesystem>

#include "change/objects.h"
#include "change_test_scene.h"
#include "cli/demo_command.h"
#include "cli/demo_report.h"
#include "cli/diff_command.h"
#include "cli/diff_overlay.h"
#include "cli/sim_command.h"
#include "core/error.h"
#include "io/image_io.h"
#include "mesh/ply.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

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

// Change detection: over the default 5-session room with noise on (the demo's settings), precision
// >= 99 % and recall >= 95 % of moved objects; >= 98 % of the static surface seen within 2 cm of
// the static mesh and <= 1 % of the static mesh's area on moved objects. Keyframe selection, in the
// same run (--incremental): fusing only the selected keyframes keeps >= 98 % of the complete map's
// coverage, and change detection on them finds the moved objects the complete run finds, within one
// (every instance and arrivals).
TEST(ChangeDemo, DefaultRoomMeetsItsTargets) {
  apps::DemoOptions options;
  options.objects = false;  // the object database step has its own test (test_objects_demo)
  options.out_dir = freshDir("strata_change_demo").string();
  options.quiet = true;
  options.incremental = true;
  const apps::DemoReport report = apps::runDemoPipeline(options);
  const change::WorldEvaluation& e = report.evaluation;
  for (const auto& session : e.sessions) {
    std::printf("[ change ] session %d: %s\n", session.session,
                change::describeCounts(session.counts).c_str());
    for (const auto& m : session.objects) {
      if (m.evaluated && !m.found) {
        std::printf("[ change ]   missed %d %s: coverage %.2f, on it %.2f\n", m.object_id,
                    m.name.c_str(), m.coverage, m.on_object);
      }
    }
  }
  std::printf(
      "[ change ] all sessions: %s; static map: %.2f %% of %zu seen points within 2 cm, "
      "%.3f %% of %.1f m2 on moved objects; %.0f s\n",
      change::describeCounts(e.totals).c_str(), 100.0 * e.static_map.completeness,
      e.static_map.seen_points, 100.0 * e.static_map.ghostShare(), e.static_map.mesh_area_m2,
      report.total_s);
  EXPECT_GE(e.totals.moved, 20u) << "the room's objects move between its sessions";
  EXPECT_GE(e.totals.precision(), 0.99);
  EXPECT_GE(e.totals.recall(), 0.95);
  EXPECT_GE(e.static_map.completeness, 0.98);
  EXPECT_LE(e.static_map.ghostShare(), 0.01);

  ASSERT_TRUE(report.incremental.has_value());
  const apps::IncrementalResult& inc = *report.incremental;
  std::printf("[ select ] %s\n", report.incremental_summary.c_str());
  EXPECT_EQ(inc.objects_complete.found, e.totals.found);
  EXPECT_GE(inc.coverage_incremental, 0.98 * inc.coverage_complete);
  EXPECT_LT(inc.images.fused, inc.images.total) << "something was left out";
  std::size_t fused = 0;
  for (const auto& session : inc.images_per_session) fused += session.fused;
  EXPECT_EQ(inc.images_per_session.size(), e.sessions.size() - 1);
  EXPECT_EQ(fused, inc.images.fused);
  for (const char* key : {"\"per_session\": [{\"fused\": ", "\"arrivals_incremental\": {",
                          "\"instances\": [{\"session\": ", "\"carried_forward\": {",
                          "\"free_space\": {\"skipped_keyframes\": ", "\"shared_samples\": ",
                          "\"depth_pixels_kept\": ", "\"arrived_samples\": ",
                          "\"free_voxel_observations\": ", "\"integration_s\": "}) {
    EXPECT_NE(report.incremental_json.find(key), std::string::npos) << key;
  }
  EXPECT_GE(inc.objects_incremental.found + 1, inc.objects_complete.found);
  EXPECT_GE(inc.objects_incremental.precision(), 0.99);
  EXPECT_GE(inc.arrivals_complete.arrivals, 10u) << "the room's objects change every session";
  EXPECT_GE(inc.arrivals_incremental.found + 1, inc.arrivals_complete.found);
  // One row per evaluated moved object of every session, and the counts agree with the rows.
  EXPECT_EQ(inc.instances.size(), inc.objects_complete.moved);
  std::size_t found_complete = 0, found_incremental = 0;
  for (const apps::InstanceOutcome& o : inc.instances) {
    found_complete += o.complete.found;
    found_incremental += o.incremental.found;
  }
  EXPECT_EQ(found_complete, inc.objects_complete.found);
  EXPECT_EQ(found_incremental, inc.objects_incremental.found);
  EXPECT_GT(inc.carried.voxels, 0u) << "confirmed places carry observations forward";
  // Free space comes from the skipped keyframes' vacated samples (their own, one per 10 x 10 px
  // cell at most, and those shared from other keyframes) and their depth kept where the place
  // around each can project: some of their pixels, not all.
  EXPECT_EQ(inc.free_space.views * 640 * 480, inc.free_space_pixels);
  EXPECT_LE(inc.free_space_shared_samples, inc.free_space.samples);
  EXPECT_LE((inc.free_space.samples - inc.free_space_shared_samples) * 100, inc.free_space_pixels);
  EXPECT_GT(inc.free_space.depth_pixels, 0u);
  EXPECT_LT(inc.free_space.depth_pixels, inc.free_space_pixels);
  // At most one arrived sample per cell of every skipped keyframe; free observations are a part
  // of all observations.
  EXPECT_LE(inc.free_space.arrived_samples * 100, inc.free_space_pixels);
  EXPECT_LE(inc.free_space.free_voxels, inc.free_space.voxels);
  fs::remove_all(options.out_dir);
}

// The demo on poses from stereo VIO (`strata demo --vio`): two sessions of the room, 30 frames
// each, 376 x 240 grey stereo (a quarter of the default's pixels: faster, and about twice the
// pose error of 752 x 480). The sessions are fused on the VIO's poses (their error against the
// truth reported: measured 25-32 mm RMSE, 45-57 mm at most, 0.9-1.2 deg), the RGB-D frame of the
// standstill before the VIO starts is skipped, and change detection still finds the moved
// objects: measured 7 of 7, precision 8 of 8 or 8 of 9 segments (in some runs one ghost where
// session 0's map and the static map disagree by the VIO's drift); the truth's poses give 7 of 7
// and 8 of 8 (about 2.5 min on 2 cores).
TEST(ChangeDemo, VioPosesKeepChangeDetection) {
  apps::DemoOptions options;
  options.objects = false;  // the object database step has its own test (test_objects_demo)
  options.out_dir = freshDir("strata_change_demo_vio").string();
  options.quiet = true;
  options.sessions = 2;
  options.frames = 30;
  options.vio.enabled = true;
  options.vio.width_px = 376;
  options.vio.height_px = 240;
  const apps::DemoReport report = apps::runDemoPipeline(options);
  ASSERT_EQ(report.sessions.size(), 2u);
  for (const apps::SessionResult& r : report.sessions) {
    ASSERT_TRUE(r.vio.has_value());
    const apps::VioSessionResult& v = *r.vio;
    std::printf(
        "[ vio ] session %d: %zu of %zu stereo frames tracked, %zu failures, first at %.2f s; "
        "fused poses vs truth: RMSE %.1f mm, max %.1f mm, %.2f deg; skipped %zu + %zu + %zu of "
        "%zu RGB-D frames\n",
        r.session, v.tracked, v.stereo_frames, v.failures, v.first_tracking_s, 1000 * v.ate_rmse_m,
        1000 * v.ate_max_m, v.rotation_rmse_deg, v.skipped_before_tracking, v.skipped_in_gaps,
        v.skipped_after_tracking, v.rgbd_frames);
    EXPECT_EQ(v.rgbd_frames, 30u);
    EXPECT_EQ(r.frames, v.fused()) << "the frames without a VIO pose are not fused";
    EXPECT_GE(v.skipped_before_tracking, 1u) << "the first frame is at t = 0, before the VIO";
    EXPECT_LE(v.skipped(), 3u);
    EXPECT_GT(v.first_tracking_s, 0.0);
    EXPECT_LT(v.first_tracking_s, 1.5) << "a standstill start within the rest";
    EXPECT_GT(v.ate_rmse_m, 0.001) << "the VIO's poses, not the truth's";
    EXPECT_LT(v.ate_rmse_m, 0.05);
    EXPECT_LT(v.ate_max_m, 0.1);
    EXPECT_LT(v.rotation_rmse_deg, 2.0);
  }
  const change::WorldEvaluation& e = report.evaluation;
  std::printf("[ vio ] change detection: %s; static map: %.1f %% seen within 2 cm\n",
              change::describeCounts(e.totals).c_str(), 100.0 * e.static_map.completeness);
  EXPECT_GE(e.totals.moved, 5u);
  EXPECT_GE(e.totals.recall(), 0.85);
  EXPECT_GE(e.totals.precision(), 0.75);
  fs::remove_all(options.out_dir);
}

}  // namespace
}  // namespace strata
