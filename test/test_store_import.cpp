// `strata map import|info|export` on sessions rendered by the simulator in-process: the exported
// keyframe trajectory is the session's odometry, keyframe selection and odometry edges follow the
// options, re-imports are skipped, and bad input exits 2; info and export never change a byte of
// the store and refuse files that are not maps; a failed first import leaves no database behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/map_command.h"
#include "cli/sim_command.h"
#include "strata/core/error.h"
#include "strata/io/tum_format.h"
#include "strata/store/session_import.h"
#include "store_test_helpers.h"
#include "test_utils.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 6;

/// One simulated session of kFrames frames (rendered once per test program).
class StoreImport : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(freshStoreDir("import"));
    for (const bool drift : {true, false}) {
      apps::SimOptions sim;
      sim.sessions = 1;
      sim.max_frames = kFrames;
      sim.drift = drift;
      sim.quiet = true;
      sim.out_dir = (*dir_ / (drift ? "sim_drift" : "sim_truth")).string();
      ASSERT_EQ(apps::runSim(sim), 0);
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path session(bool drift) {
    return *dir_ / (drift ? "sim_drift" : "sim_truth") / "session_0";
  }
  static fs::path* dir_;
};
fs::path* StoreImport::dir_ = nullptr;

TEST_F(StoreImport, ExportGivesBackTheSessionOdometry) {
  const fs::path db = *dir_ / "every_frame.sqlite";
  apps::MapOptions o;
  o.action = "import";
  o.db_path = db.string();
  o.session_dirs = {session(true).string()};
  o.keyframe_every = 1;
  o.quiet = true;
  ASSERT_EQ(apps::runMap(o), 0);
  o.action = "export";
  o.out_dir = (*dir_ / "export").string();
  ASSERT_EQ(apps::runMap(o), 0);
  const auto source = tum::readTrajectory((session(true) / "odometry.txt").string());
  const auto exported =
      tum::readTrajectory((*dir_ / "export" / "session_0" / "odometry.txt").string());
  ASSERT_EQ(source.size(), std::size_t{kFrames});
  ASSERT_EQ(exported.size(), source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    EXPECT_NEAR(exported[i].timestamp_s, source[i].timestamp_s, 1e-6) << i;
    EXPECT_TRUE(exported[i].T_W_C.isApprox(source[i].T_W_C, 1e-8)) << i;
  }
  // No optimised poses yet: no optimised.txt.
  EXPECT_FALSE(fs::exists(*dir_ / "export" / "session_0" / "optimised.txt"));

  store::Store store(db.string());
  const auto sessions = store.sessions();
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].source_folder, session(true).string());
  const auto keyframes = store.keyframes(sessions[0].id);
  // Odometry edges join consecutive keyframes with their relative odometry pose.
  const auto edges = store.edges(store::EdgeKind::kOdometry);
  ASSERT_EQ(edges.size(), keyframes.size() - 1);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    EXPECT_EQ(edges[i].from_keyframe, keyframes[i].id);
    EXPECT_EQ(edges[i].to_keyframe, keyframes[i + 1].id);
    EXPECT_TRUE((keyframes[i].T_S_C * edges[i].T_from_to).isApprox(keyframes[i + 1].T_S_C, 1e-9));
    EXPECT_DOUBLE_EQ(edges[i].information(0, 0), 1e4);  // 1 cm
    EXPECT_DOUBLE_EQ(edges[i].information(5, 5), 1e4);  // 0.01 rad
  }
  // Depth and colour of every keyframe, referenced with their checksums.
  EXPECT_EQ(store.resources().size(), 2 * keyframes.size());
  EXPECT_TRUE(store.verifyResources().empty());

  // With optimised poses, export writes them too.
  store.setOptimisedPoses({{keyframes[0].id, samplePose(1)}, {keyframes[2].id, samplePose(2)}});
  ASSERT_EQ(apps::runMap(o), 0);
  const auto optimised =
      tum::readTrajectory((*dir_ / "export" / "session_0" / "optimised.txt").string());
  ASSERT_EQ(optimised.size(), 2u);
  EXPECT_TRUE(optimised[1].T_W_C.isApprox(samplePose(2), 1e-8));
}

TEST_F(StoreImport, KeyframeOptionsReimportAndGroundTruthFallback) {
  const fs::path db = *dir_ / "options.sqlite";
  store::Store store(db.string());
  store::ImportOptions options;
  options.keyframe_every = 2;
  std::size_t last_done = 0;
  const auto result = store::importTumSession(
      store, session(true).string(), options,
      [&](std::size_t done, std::size_t total) { last_done = done + 100 * total; });
  EXPECT_FALSE(result.skipped);
  EXPECT_EQ(result.frames, std::size_t{kFrames});
  EXPECT_EQ(result.keyframes, std::size_t{kFrames / 2});  // frames 0, 2, 4
  EXPECT_EQ(last_done, 3u + 300u);
  const auto source = tum::readTrajectory((session(true) / "odometry.txt").string());
  const auto keyframes = store.keyframes(result.session_id);
  ASSERT_EQ(keyframes.size(), 3u);
  EXPECT_TRUE(keyframes[1].T_S_C.isApprox(source[2].T_W_C, 1e-9));

  const auto again = store::importTumSession(store, session(true).string() + "/", options);
  EXPECT_TRUE(again.skipped);
  EXPECT_EQ(again.session_id, result.session_id);
  EXPECT_EQ(store.sessions().size(), 1u);

  // No odometry.txt: groundtruth.txt is the odometry. Keyframes by motion alone.
  options.keyframe_every = 0;
  options.keyframe_distance_m = 1e-6;
  const auto truth = store::importTumSession(store, session(false).string(), options);
  EXPECT_EQ(fs::path(truth.odometry_file).filename(), "groundtruth.txt");
  EXPECT_EQ(truth.keyframes, std::size_t{kFrames});
  options.keyframe_distance_m = 0.0;
  EXPECT_THROW(store::importTumSession(store, session(false).string(), options), InputError);
}

TEST_F(StoreImport, InfoPrintsCountsAndBadInputExitsTwo) {
  const fs::path db = *dir_ / "info.sqlite";
  apps::MapOptions o;
  o.action = "import";
  o.db_path = db.string();
  o.session_dirs = {session(true).string(), session(false).string()};
  o.keyframe_every = 3;
  o.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runMap(o), 0);
  o.session_dirs = {session(true).string()};
  ASSERT_EQ(apps::runMap(o), 0);  // skipped, with a message
  o.action = "info";
  o.json = true;
  o.verify = true;
  ASSERT_EQ(apps::runMap(o), 0);
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_NE(out.find("already in"), std::string::npos) << out;
  EXPECT_NE(out.find("\"keyframes\": 2"), std::string::npos) << out;
  EXPECT_NE(out.find("\"resource_problems\": []"), std::string::npos) << out;

  // A changed resource makes --verify exit 2.
  const fs::path depth = session(false) / "depth" / "000000.png";
  const std::string saved = readText(depth);
  std::ofstream(depth, std::ios::binary | std::ios::app) << "x";
  testing::internal::CaptureStdout();
  EXPECT_EQ(apps::runMap(o), 2);
  EXPECT_NE(testing::internal::GetCapturedStdout().find("size_changed"), std::string::npos);
  std::ofstream(depth, std::ios::binary | std::ios::trunc) << saved;

  testing::internal::CaptureStderr();
  o.db_path = (*dir_ / "absent.sqlite").string();
  EXPECT_EQ(apps::runMap(o), 2);
  o.action = "import";
  o.db_path = db.string();
  o.session_dirs = {(*dir_ / "no_such_session").string()};
  EXPECT_EQ(apps::runMap(o), 2);
  const std::string errors = testing::internal::GetCapturedStderr();
  EXPECT_NE(errors.find("absent.sqlite' does not exist"), std::string::npos) << errors;
  EXPECT_NE(errors.find("no_such_session"), std::string::npos) << errors;
}

TEST_F(StoreImport, ReadingCommandsNeverWriteAndFailedImportsLeaveNoDatabase) {
  const fs::path db = *dir_ / "read_only.sqlite";
  apps::MapOptions o;
  o.action = "import";
  o.db_path = db.string();
  o.session_dirs = {session(true).string()};
  o.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runMap(o), 0);
  testing::internal::GetCapturedStdout();
  const std::string before = readText(db);

  // info and export leave the map byte for byte as it was.
  o.action = "info";
  testing::internal::CaptureStdout();
  EXPECT_EQ(apps::runMap(o), 0);
  o.action = "export";
  o.out_dir = (*dir_ / "read_only_export").string();
  EXPECT_EQ(apps::runMap(o), 0);
  testing::internal::GetCapturedStdout();
  EXPECT_EQ(readText(db), before);

  // An empty file and a file that is not SQLite stay as they were and are named.
  const fs::path empty = *dir_ / "empty.sqlite";
  std::ofstream(empty).close();
  const fs::path text = *dir_ / "notes.sqlite";
  std::ofstream(text) << "not a database\n";
  testing::internal::CaptureStderr();
  for (const fs::path& bad : {empty, text}) {
    for (const char* action : {"info", "export"}) {
      o.action = action;
      o.db_path = bad.string();
      o.out_dir = (*dir_ / "bad_export").string();
      EXPECT_EQ(apps::runMap(o), 2) << action << " " << bad;
    }
  }
  const std::string errors = testing::internal::GetCapturedStderr();
  EXPECT_NE(errors.find("empty.sqlite' is empty, not a Strata map"), std::string::npos) << errors;
  EXPECT_NE(errors.find("notes.sqlite"), std::string::npos) << errors;
  EXPECT_EQ(fs::file_size(empty), 0u);
  EXPECT_EQ(readText(text), "not a database\n");
  EXPECT_FALSE(fs::exists(*dir_ / "bad_export"));

  // The export folder may not be the database itself.
  o.action = "export";
  o.db_path = db.string();
  o.out_dir = db.string();
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runMap(o), 2);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(readText(db), before);

  // A first import that fails (a folder that is not a session) leaves no database.
  const fs::path fresh = *dir_ / "fresh.sqlite";
  const fs::path not_a_session = *dir_ / "not_a_session";
  fs::create_directories(not_a_session);
  o.action = "import";
  o.db_path = fresh.string();
  o.session_dirs = {not_a_session.string()};
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runMap(o), 2);
  testing::internal::GetCapturedStderr();
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_FALSE(fs::exists(fresh.string() + "-wal"));
}

}  // namespace
}  // namespace strata::test
