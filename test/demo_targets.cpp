#include "demo_targets.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "strata/change/object_discovery.h"
#include "strata/objects/eval/object_db_eval.h"
#include "test_utils.h"

namespace strata::test {

namespace fs = std::filesystem;

apps::DemoOptions roomDemoOptions(const std::string& name) {
  apps::DemoOptions options;
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  options.out_dir = dir.string();
  options.quiet = true;
  return options;
}

apps::DemoOptions roomVioDemoOptions(const std::string& name, int frames) {
  apps::DemoOptions options = roomDemoOptions(name);
  options.objects = false;
  options.sessions = 2;
  options.frames = frames;
  options.vio.enabled = true;
  options.vio.width_px = 376;
  options.vio.height_px = 240;
  return options;
}

void expectRoomChangeTargets(const apps::DemoReport& report, std::size_t min_moved,
                             std::size_t min_arrivals) {
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
  EXPECT_GE(e.totals.moved, min_moved) << "the room's objects move between its sessions";
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
  const nlohmann::json incremental = nlohmann::json::parse(report.incremental_json);
  for (const char* key :
       {"/keyframes_after_first_session/per_session/0/fused", "/arrivals_incremental/recall",
        "/instances/0/session", "/carried_forward/voxels", "/free_space/skipped_keyframes",
        "/free_space/shared_samples", "/free_space/depth_pixels_kept",
        "/free_space/arrived_samples", "/free_space/free_voxel_observations",
        "/free_space/integration_s"}) {
    EXPECT_TRUE(incremental.contains(nlohmann::json::json_pointer(key))) << key;
  }
  EXPECT_GE(inc.objects_incremental.found + 1, inc.objects_complete.found);
  EXPECT_GE(inc.objects_incremental.precision(), 0.99);
  EXPECT_GE(inc.arrivals_complete.arrivals, min_arrivals) << "the room's objects change every session";
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
}

void expectVioDemoTargets(const apps::DemoReport& report, std::size_t sessions, std::size_t frames,
                          std::size_t min_moved) {
  ASSERT_EQ(report.sessions.size(), sessions);
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
    EXPECT_EQ(v.rgbd_frames, frames);
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
  EXPECT_GE(e.totals.moved, min_moved);
  EXPECT_GE(e.totals.recall(), 0.85);
  EXPECT_GE(e.totals.precision(), 0.75);
}

void expectRoomObjectTargets(const apps::DemoReport& report, const std::string& out_dir,
                             std::size_t min_same_object, double min_recall,
                             double min_main_recall) {
  ASSERT_TRUE(report.objects.has_value());
  const eval::ObjectDbEvaluation& e = *report.objects;
  std::printf("[ objects ] room: %s\n", eval::describeObjectDbEvaluation(e).c_str());
  std::printf("[ objects ] %zu segments, %zu in models; pose max %.1f mm / %.2f deg\n", e.segments,
              e.segments_in_models, 1000.0 * e.pose.max_translation_m, e.pose.max_rotation_deg);
  for (const eval::ModelEvaluation& m : e.models) {
    std::printf(
        "[ objects ]   model %d: %s (%d), %d instances in %d sessions, area %.3f m2, "
        "completeness %.2f, growth %.2f, accuracy %.1f mm, pose max %.1f mm / %.1f deg\n",
        m.model_id, m.name.c_str(), m.object_id, m.instances, m.sessions, m.area_m2, m.completeness,
        m.growth, 1000.0 * m.accuracy_m, 1000.0 * m.pose_max_translation_m,
        m.pose_max_rotation_deg);
  }
  EXPECT_GE(e.pairs.same_object, min_same_object) << "objects of the room move more than once";
  EXPECT_GE(e.pairs.precision(), 0.99);
  // Target: recall >= 0.9. Measured with 4-DoF registration, the height check, the score's
  // fitness taken both ways, joining and the floor fixing the height: 60.5 % over all pairs of
  // segments of one object, 89.2 % between each object's main segments (63.6 / 91.6 % with the
  // height estimated: two chair views then passed the SDF agreement at 0.75 that now score
  // 0.74-0.75; the warehouse and the office gained). The gap is over-segmented chair parts
  // founding models of their own (the size prefilter and the height check keep them from the
  // chair's model) and partial views refused by the SDF agreement or the free-space test.
  EXPECT_GE(e.pairs.recall(), min_recall);
  EXPECT_GE(e.pairs.mainRecall(), min_main_recall);
  EXPECT_GT(e.pose.pairs, 0u);
  EXPECT_LE(e.pose.median_translation_m, 0.01);
  EXPECT_LE(e.pose.median_rotation_deg, 2.0);
  EXPECT_LT(e.growth_max, 2.0) << "no model grows into a ball of merged shapes";
  const fs::path out(out_dir);
  const nlohmann::json report_json = nlohmann::json::parse(test::readText(out / "report.json"));
  EXPECT_TRUE(report_json.contains(nlohmann::json::json_pointer("/objects/models")));
  EXPECT_TRUE(fs::exists(out / "objects.json"));
  EXPECT_TRUE(fs::exists(out / "objects.sodb"));
  EXPECT_TRUE(fs::exists(out / "objects.png"));
}

}  // namespace strata::test
