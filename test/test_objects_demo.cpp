// The object database end to end: `strata objects` on simulated sessions (files, truth found beside
// the folders, bad input) and the demo's last step on the default room against its targets.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/demo_command.h"
#include "cli/demo_report.h"
#include "cli/objects_command.h"
#include "cli/sim_command.h"
#include "demo_targets.h"
#include "strata/io/image_io.h"
#include "strata/mesh/ply.h"
#include "strata/objects/object_database_file.h"
#include "test_utils.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

// Pairs of segments of one object the truth counts in the CI run below (measured: 16).
constexpr std::size_t kThreeSessionPairs = 14;

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  return dir;
}

TEST(ObjectsCommand, BadInputExitsTwoNamingIt) {
  apps::ObjectsOptions options;
  const fs::path missing = freshDir("strata_objects_missing");
  options.sessions = {missing.string(), missing.string() + "_too"};
  options.out_dir = freshDir("strata_objects_missing_out").string();
  options.quiet = true;
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runObjects(options), 2);
  std::string message = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(options.out_dir)) << "nothing is written before the inputs are checked";
  // One session: nothing can have moved.
  fs::create_directories(missing);
  options.sessions = {missing.string()};
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runObjects(options), 2);
  message = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find("at least two sessions"), std::string::npos) << message;
  options.sessions = {missing.string(), missing.string()};
  options.frames = -1;
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runObjects(options), 2);
  message = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find("--frames"), std::string::npos) << message;
  fs::remove_all(missing);
}

// Three sessions of the room, 30 frames each at 4 cm voxels: every output is written and the
// truth is found beside the session folders.
TEST(ObjectsCommand, SimulatedSessionsWriteEveryOutputAndTheirScore) {
  const fs::path sim = freshDir("strata_objects_sim");
  apps::SimOptions sim_options;
  sim_options.sessions = 3;
  sim_options.max_frames = 30;
  sim_options.out_dir = sim.string();
  sim_options.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runSim(sim_options), 0);
  testing::internal::GetCapturedStdout();
  apps::ObjectsOptions options;
  for (int s = 0; s < 3; ++s) {  // the last with a trailing slash, as shells complete folders
    options.sessions.push_back((sim / ("session_" + std::to_string(s))).string() +
                               (s == 2 ? "/" : ""));
  }
  options.out_dir = freshDir("strata_objects_out").string();
  options.min_weight = 3.0f;
  options.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runObjects(options), 0);
  const std::string summary = testing::internal::GetCapturedStdout();
  std::printf("[ objects ] %s\n", summary.c_str());
  EXPECT_NE(summary.find("against the truth of world 'room'"), std::string::npos) << summary;
  const fs::path out(options.out_dir);
  const nlohmann::json json = nlohmann::json::parse(test::readText(out / "objects.json"));
  EXPECT_TRUE(json.at("models").is_array());
  EXPECT_TRUE(json.at("segments").is_array());
  for (const char* key : {"/truth/pairs/precision", "/models/0/instances/0/T_W_O/3/3",
                          "/models/0/instances/0/centroid_m/2",
                          "/models/0/instances/0/match_score"}) {
    EXPECT_TRUE(json.contains(nlohmann::json::json_pointer(key))) << key;
  }
  const objects::ObjectDatabase db = objects::loadObjectDatabase((out / "objects.sodb").string());
  EXPECT_GE(db.models().size(), 1u) << "the room's objects move every session";
  for (const auto& model : db.models()) {
    const fs::path ply = out / ("model_" + std::to_string(model.id) + ".ply");
    ASSERT_TRUE(fs::exists(ply)) << ply;
    EXPECT_FALSE(readPly(ply.string()).empty()) << ply;
  }
  for (int s = 0; s < 3; ++s) {
    const fs::path ply = out / ("session_" + std::to_string(s) + "_completed.ply");
    ASSERT_TRUE(fs::exists(ply)) << ply;
    EXPECT_FALSE(readPly(ply.string()).empty());
  }
  const ColorImage sheet = readColorImage((out / "objects.png").string());
  EXPECT_GE(sheet.width_px, 200);
  fs::remove_all(sim);
  fs::remove_all(out);
}

// The demo's last step on the first three of the room's five sessions (the demo's settings: 60
// frames per session, noise on): the CI run of ObjectsDemo.DefaultRoomMeetsItsTargets, which
// test_demo_long runs over all five (about 2 min on 2 cores, labelled long). Targets as there
// (demo_targets.h) over the pairs three sessions give; measured (62 s): precision 100 % (10/10),
// recall 62.5 % (10/16), main segments 71.4 % (10/14: the five-session run's 89 % comes from the
// later sessions' views), pose median 3.0 mm / 0.19 deg.
TEST(ObjectsDemo, FirstThreeRoomSessionsMeetTheTargets) {
  apps::DemoOptions options = test::roomDemoOptions("strata_objects_demo");
  options.sessions = 3;
  const apps::DemoReport report = apps::runDemoPipeline(options);
  test::expectRoomObjectTargets(report, options.out_dir, kThreeSessionPairs, 0.56, 0.65);
  fs::remove_all(options.out_dir);
}

}  // namespace
}  // namespace strata
