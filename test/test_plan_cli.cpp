// `strata plan` and `strata topo` in-process on a saved map of the analytic room (the ESDF runs on
// the device): the path through the door and its files, no path with the door closed, bad input
// named with a non-zero exit, the topological map's files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/plan_command.h"
#include "cli/topo_command.h"
#include "strata/io/image_io.h"
#include "strata/map/map_file.h"
#include "plan_room_scene.h"
#include "test_utils.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

class PlanCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("strata_plan_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    saveMap(test::PlanRoom{}.tsdf(), path("room.strata"));
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  apps::PlanOptions options(const std::string& planner) const {
    apps::PlanOptions o;
    o.map_path = path("room.strata");
    o.from = "1.05,0.55,0.55";
    o.to = "2.95,0.55,0.55";
    o.planner = planner;
    o.radius_m = 0.2f;
    o.esdf_max_distance_m = 1.0f;
    o.out_dir = path("out_" + planner);
    return o;
  }

  int plan(const apps::PlanOptions& o) {
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    const int code = apps::runPlan(o);
    stdout_ = testing::internal::GetCapturedStdout();
    stderr_ = testing::internal::GetCapturedStderr();
    return code;
  }

  fs::path dir_;
  std::string stdout_, stderr_;
};

TEST_F(PlanCliTest, PlansThroughTheDoorAndWritesTheFiles) {
  for (const std::string planner : {"grid", "topo", "rrt"}) {
    const apps::PlanOptions o = options(planner);
    ASSERT_EQ(plan(o), 0) << planner << ": " << stderr_;
    const fs::path out(o.out_dir);
    const std::string csv = test::readText(out / "path.csv");
    EXPECT_EQ(csv.rfind("x,y,z\n1.0500,0.5500,0.5500\n", 0), 0u) << csv;
    EXPECT_NE(csv.find("2.9500,0.5500,0.5500\n"), std::string::npos) << csv;
    const std::string report = test::readText(out / "report.json");
    EXPECT_NE(report.find("\"planner\": \"" + planner + "\""), std::string::npos) << report;
    EXPECT_NE(report.find("\"success\": true"), std::string::npos) << report;
    for (const char* key : {"length_m", "min_clearance_m", "planning_ms", "build_ms",
                            "collision_checks", "memory_bytes"}) {
      EXPECT_NE(report.find(key), std::string::npos) << key;
    }
    const ColorImage png = readColorImage((out / "path.png").string());
    EXPECT_GT(png.width_px, 400);
    EXPECT_NE(stdout_.find(planner + " path of"), std::string::npos) << stdout_;
  }
}

TEST_F(PlanCliTest, NoPathWhenTheDoorIsClosed) {
  test::PlanRoom closed;
  closed.door_open = false;
  saveMap(closed.tsdf(), path("closed.strata"));
  apps::PlanOptions o = options("topo");
  o.map_path = path("closed.strata");
  EXPECT_EQ(plan(o), 1);
  EXPECT_NE(stderr_.find("not connected"), std::string::npos) << stderr_;
  EXPECT_NE(test::readText(fs::path(o.out_dir) / "report.json").find("\"success\": false"),
            std::string::npos);
}

TEST_F(PlanCliTest, BadInputIsNamed) {
  struct Case {
    std::string what;
    apps::PlanOptions o;
    std::string expected;
  };
  std::vector<Case> cases;
  apps::PlanOptions o = options("grid");
  o.map_path = path("missing.strata");
  cases.push_back({"missing map", o, "missing.strata"});
  std::ofstream(path("corrupt.strata")) << "not a map";
  o = options("grid");
  o.map_path = path("corrupt.strata");
  cases.push_back({"corrupt map", o, "corrupt.strata"});
  o = options("grid");
  o.from = "1.0,2.0";
  cases.push_back({"two numbers", o, "--from"});
  o = options("grid");
  o.to = "1.0,nan,0.5";
  cases.push_back({"NaN", o, "--to"});
  o = options("grid");
  o.from = "2.05,0.55,0.55";  // inside the wall
  cases.push_back({"start in the wall", o, "start (--from) (2.05, 0.55, 0.55) is in collision"});
  o = options("topo");
  o.to = "20,0.5,0.5";
  cases.push_back({"goal outside", o, "goal (--to) (20.00, 0.50, 0.50) is outside the map"});
  o = options("dijkstra");
  cases.push_back({"unknown planner", o, "unknown planner 'dijkstra'"});
  o = options("grid");
  o.unknown = "maybe";
  cases.push_back({"policy", o, "--unknown"});
  for (const Case& c : cases) {
    EXPECT_EQ(plan(c.o), 2) << c.what;
    EXPECT_NE(stderr_.find(c.expected), std::string::npos) << c.what << ": " << stderr_;
  }
}

TEST_F(PlanCliTest, TopoWritesTheMapAndItsPicture) {
  apps::TopoOptions o;
  o.map_path = path("room.strata");
  o.radius_m = 0.2f;
  o.esdf_max_distance_m = 1.0f;
  o.out_dir = path("topo");
  testing::internal::CaptureStdout();
  const int code = apps::runTopo(o);
  const std::string out = testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  const std::string json = test::readText(fs::path(o.out_dir) / "topo.json");
  for (const char* key : {"\"cluster_count\"", "\"portal_count\"", "\"edges\"", "\"build_ms\"",
                          "\"memory_bytes\"", "\"grid_memory_bytes\"", "\"clusters\""}) {
    EXPECT_NE(json.find(key), std::string::npos) << key;
  }
  const ColorImage png = readColorImage((fs::path(o.out_dir) / "topo.png").string());
  EXPECT_GE(std::max(png.width_px, png.height_px), 640);
  EXPECT_NE(out.find("clusters"), std::string::npos);
  o.map_path = path("missing.strata");
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runTopo(o), 2);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("missing.strata"), std::string::npos);
}

}  // namespace
}  // namespace strata
