// Alignment of a map database's sessions on real data: the 7-Scenes redkitchen excerpt split in
// two sessions, the second in a frame of its own with drifted odometry; its offset is recovered.
// Also what the store holds afterwards, re-alignment replacing the old result, and sessions whose
// files changed since the import refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "strata/align/store_alignment.h"
#include "cli/align_command.h"
#include "strata/core/error.h"
#include "strata/io/odometry_frame_file.h"
#include "strata/sim/session/drifted_session.h"
#include "strata/store/session_import.h"
#include "split_kitchen.h"
#include "store_test_helpers.h"
#include "test_utils.h"

namespace strata::align {
namespace {

namespace fs = std::filesystem;

using test::SplitKitchen;

/// Frames 0-74 as the anchor (odometry = the reference poses), 75-149 offset and drifting.
SplitKitchen splitKitchen(const std::string& kitchen, const std::string& name) {
  return test::splitKitchen(kitchen, name, "kitchen_a", "kitchen_b",
                            sim::DriftConfig{}.translation_sigma_m_per_sqrt_m);
}

std::unique_ptr<store::Store> importBoth(const SplitKitchen& split) {
  auto db = std::make_unique<store::Store>((split.root / "map.sqlite").string());
  store::ImportOptions import;
  import.keyframe_every = 3;
  for (const fs::path& dir : {split.first, split.second})
    store::importTumSession(*db, dir.string(), import);
  return db;
}

double angleDeg(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle() * 180.0 / M_PI; }

TEST(AlignStore, RedkitchenSplitInTwoRecoversTheSecondHalfsOffset) {
  STRATA_REQUIRE_DATA("redkitchen", kitchen);
  const SplitKitchen split = splitKitchen(kitchen, "align_kitchen");
  EXPECT_TRUE(readOdometryFrame((split.second / "odometry_frame.txt").string())
                  .isApprox(split.T_W_S_second, 1e-6));
  auto db = importBoth(split);
  const StoreAlignment a = alignStore(*db);
  ASSERT_EQ(a.result.sessions.size(), 2u);
  ASSERT_TRUE(a.result.sessions[1].aligned);
  // The offset's error at the second half's first camera (at the odometry origin, metres away,
  // every 0.1 degree of rotation error would add millimetres per metre of lever arm).
  const Eigen::Isometry3d& T_S_C0 = a.result.sessions[1].frame_T_S_C.front();
  const Eigen::Isometry3d error =
      (split.T_W_S_second * T_S_C0).inverse() * *a.result.sessions[1].T_W_S * T_S_C0;
  std::printf("redkitchen split: offset recovered within %.1f mm and %.3f deg (%zu loops kept of "
              "%zu verified, %zu candidates)\n",
              1e3 * error.translation().norm(), angleDeg(error.linear()),
              static_cast<std::size_t>(std::count_if(a.result.loops.begin(), a.result.loops.end(),
                                                     [](const AlignLoop& l) { return l.accepted; })),
              a.result.loops.size(), a.result.candidates);
  EXPECT_LT(error.translation().norm(), 0.02);
  EXPECT_LT(angleDeg(error.linear()), 1.0);

  // The store holds the result: both sessions aligned, the anchor at identity, loops as edges.
  const std::vector<store::SessionRecord> sessions = db->sessions();
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_TRUE(sessions[0].aligned && sessions[1].aligned);
  EXPECT_TRUE(sessions[0].T_W_S->isApprox(Eigen::Isometry3d::Identity(), 1e-9));
  const std::size_t loops = db->edges(store::EdgeKind::kLoop).size();
  EXPECT_EQ(loops, a.result.loops.size());
  EXPECT_GT(loops, 0u);
  for (const store::KeyframeRecord& k : db->keyframes(sessions[1].id)) EXPECT_TRUE(k.T_W_C);
  EXPECT_TRUE(db->features(db->keyframes(sessions[0].id).front().id).has_value());

  // Aligning again replaces the result (stored features reused), it does not add to it.
  const StoreAlignment again = alignStore(*db);
  EXPECT_EQ(db->edges(store::EdgeKind::kLoop).size(), again.result.loops.size());
  ASSERT_TRUE(again.result.sessions[1].aligned);
  EXPECT_LT((*again.result.sessions[1].T_W_S).translation().x() -
                (*a.result.sessions[1].T_W_S).translation().x(),
            1e-6);
  fs::remove_all(split.root);
}

TEST(AlignStore, ASessionWhoseFolderIsGoneIsRefusedAndTheStoreKeptAsItWas) {
  STRATA_REQUIRE_DATA("redkitchen", kitchen);
  const SplitKitchen split = splitKitchen(kitchen, "align_changed");
  auto db = importBoth(split);
  fs::rename(split.second, split.root / "moved");  // the second session's folder is gone
  try {
    alignStore(*db);
    FAIL() << "a session whose folder is gone was aligned";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("kitchen_b"), std::string::npos) << e.what();
  }
  for (const store::SessionRecord& s : db->sessions()) EXPECT_FALSE(s.aligned);
  EXPECT_TRUE(db->edges(store::EdgeKind::kLoop).empty());
  fs::remove_all(split.root);
}

TEST(AlignCli, WritesTrajectoriesLoopsReportAndPictureAndScoresAgainstTheTruth) {
  STRATA_REQUIRE_DATA("redkitchen", kitchen);
  const SplitKitchen split = splitKitchen(kitchen, "align_cli");
  apps::AlignOptions o;
  o.session_dirs = {split.first.string(), split.second.string()};
  o.out_dir = (split.root / "out").string();
  o.keyframe_every = 3;
  o.quiet = true;
  ASSERT_EQ(apps::runAlign(o), 0);
  const fs::path out = split.root / "out";
  for (const char* file : {"map.sqlite", "loops.csv", "report.json", "trajectories.png",
                           "session_0/trajectory.txt", "session_1/trajectory.txt"}) {
    EXPECT_TRUE(fs::exists(out / file)) << file;
  }
  const std::string report = test::readText(out / "report.json");
  EXPECT_NE(report.find("\"aligned_sessions\": 2"), std::string::npos) << report;
  EXPECT_NE(report.find("\"loops_accepted_false\": 0"), std::string::npos) << report;
  // 75 frames per session, one line each after the header.
  const std::string trajectory = test::readText(out / "session_1/trajectory.txt");
  EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), 76);
  const std::string loops = test::readText(out / "loops.csv");
  EXPECT_GT(std::count(loops.begin(), loops.end(), '\n'), 10);
  EXPECT_NE(loops.find("true_loop"), std::string::npos);  // scored against groundtruth.txt

  // Running again on the database alone replaces the result in place.
  apps::AlignOptions again;
  again.db_path = (out / "map.sqlite").string();
  again.quiet = true;
  EXPECT_EQ(apps::runAlign(again), 0);
  fs::remove_all(split.root);
}

TEST(AlignCli, BadInputExitsTwoNamingTheProblem) {
  apps::AlignOptions none;
  EXPECT_EQ(apps::runAlign(none), 2);  // neither folders nor --db
  const fs::path root = test::freshStoreDir("align_cli_bad");
  apps::AlignOptions missing;
  missing.session_dirs = {(root / "no_such_session").string()};
  missing.out_dir = (root / "out").string();
  missing.quiet = true;
  EXPECT_EQ(apps::runAlign(missing), 2);
  apps::AlignOptions no_db;
  no_db.db_path = (root / "absent.sqlite").string();
  EXPECT_EQ(apps::runAlign(no_db), 2);
  apps::AlignOptions no_out;
  no_out.session_dirs = {root.string()};
  EXPECT_EQ(apps::runAlign(no_out), 2);  // folders need --out
  fs::remove_all(root);
}

}  // namespace
}  // namespace strata::align
