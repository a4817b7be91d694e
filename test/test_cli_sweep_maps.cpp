// Bad input swept through the map commands in-process (plan, topo, explore, align, objects,
// diff, select, demo): bad numbers and names, missing files, files that are not what they should
// be, outputs over inputs, outputs that cannot be written. Every row fails before any work (no
// device is opened, so the sweep runs on the host) with the exit code for bad input, a message
// naming the option or file, its inputs byte for byte as they were and no output left behind.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "change_test_scene.h"
#include "cli/align_command.h"
#include "cli/demo_command.h"
#include "cli/diff_command.h"
#include "cli/explore_command.h"
#include "cli/objects_command.h"
#include "cli/plan_command.h"
#include "cli/select_command.h"
#include "cli/topo_command.h"
#include "plan_room_scene.h"
#include "strata/map/map_file.h"
#include "strata/store/session_store.h"
#include "cli_sweep.h"
#include "test_utils.h"

namespace strata {
namespace {

namespace fs = std::filesystem;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using Row = test::SweepRow;

template <typename Options>
std::function<int()> call(int (*run)(const Options&), const Options& options) {
  return [run, options] { return run(options); };
}

class CliSweepMaps : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::freshTempDir(
        std::string("cli_sweep_") +
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    saveMap(test::PlanRoom{}.tsdf(), path("room.strata"));
    // A map on another grid: 20 cm voxels over a corner of the room.
    const test::PlanRoom room;
    saveMap(test::makeSdfMap([&room](const Eigen::Vector3d& p) { return room.signedDistance(p); },
                             Eigen::Vector3d(-0.3, -0.3, -0.3), Eigen::Vector3d(1.0, 1.0, 1.0),
                             0.2f, [](const Eigen::Vector3d&) { return true; }),
            path("coarse.strata"));
    write("not_a_map.strata", "not a map\n");
    write("a_file.txt", "a file, not a folder\n");
    write("not_a_world.yaml", "not a world\n");
    write("not_a_db.sqlite", "not a database\n");
    // Maps named like the files the commands write, in a folder given as --out.
    fs::create_directories(path("over"));
    for (const char* name : {"report.json", "topo.json", "keyframes.csv"}) {
      fs::copy_file(path("room.strata"), path(std::string("over/") + name));
    }
    fs::create_directories(path("png_is_a_folder/path.png"));
    fs::create_directories(path("session_a"));
    fs::create_directories(path("session_b"));
    write("session_a/rgb.txt", "# nothing\n");
    write("trajectories/report.json", "0 0 0 0 0 0 0 1\n");
    // A session that imports (odometry alone) but cannot be aligned (no images to read).
    write("gt_only/groundtruth.txt",
          "0.0 0 0 0 0 0 0 1\n0.1 0.1 0 0 0 0 0 1\n0.2 0.2 0 0 0 0 0 1\n");
    { store::Store empty(path("empty.sqlite")); }
    fs::create_directories(path("db_out"));
    { store::Store named(path("db_out/report.json")); }
    root_ = ::geteuid() == 0;
    if (!root_) {
      fs::create_directories(path("locked"));
      ::chmod(path("locked").c_str(), 0555);
    }
  }
  void TearDown() override {
    ::chmod(path("locked").c_str(), 0755);
    fs::remove_all(dir_);
  }

  fs::path path(const std::string& name) const { return dir_ / name; }
  void write(const std::string& name, const std::string& text) const {
    fs::create_directories(path(name).parent_path());
    std::ofstream(path(name), std::ios::binary) << text;
  }

  /// Runs every row (test/cli_sweep.h); returns the row count.
  std::size_t sweep(const std::string& command, const std::vector<Row>& rows) {
    return test::sweepRows(command, rows, dir_);
  }

  fs::path dir_;
  bool root_ = false;
};

TEST_F(CliSweepMaps, Plan) {
  const auto good = [&] {
    apps::PlanOptions o;
    o.map_path = path("room.strata").string();
    o.from = "1.05,0.55,0.55";
    o.to = "2.95,0.55,0.55";
    o.radius_m = 0.2f;
    o.esdf_max_distance_m = 1.0f;
    o.out_dir = path("out").string();
    return o;
  };
  const fs::path map = path("room.strata"), out = path("out");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what, const std::function<void(apps::PlanOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::PlanOptions o = good();
    edit(o);
    unchanged.push_back(map);
    absent.push_back(out);
    rows.push_back({what, call(apps::runPlan, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("an unknown planner, with the start in the wall",
      [](auto& o) { o.planner = "dijkstra", o.from = "2.05,0.55,0.55"; },
      {"--planner", "unknown planner 'dijkstra'", "grid, topo or rrt"});
  add("a negative radius", [](auto& o) { o.radius_m = -0.1f; }, {"--radius", ">= 0"});
  add("a NaN radius", [](auto& o) { o.radius_m = kNaN; }, {"--radius", ">= 0"});
  add("a radius the ESDF cannot hold", [](auto& o) { o.radius_m = 1.5f; },
      {"--radius", "--esdf-max-distance"});
  add("an infinite ESDF distance",
      [](auto& o) { o.esdf_max_distance_m = std::numeric_limits<float>::infinity(); },
      {"--esdf-max-distance", "> 0"});
  add("a NaN in --from", [](auto& o) { o.from = "1,nan,0.5"; }, {"--from", "finite"});
  add("two numbers in --to", [](auto& o) { o.to = "1,2"; }, {"--to", "three"});
  add("an unknown policy", [](auto& o) { o.unknown = "maybe"; }, {"--unknown", "occupied"});
  add("no --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("a missing map", [&](auto& o) { o.map_path = path("missing.strata").string(); },
      {"missing.strata"});
  add("a map that is not a map", [&](auto& o) { o.map_path = path("not_a_map.strata").string(); },
      {"not_a_map.strata", "not a Strata map"}, {path("not_a_map.strata")});
  add("--out is the map", [&](auto& o) { o.out_dir = map.string(); }, {"--out", "room.strata"});
  add("--out/report.json is the map",
      [&](auto& o) {
        o.map_path = path("over/report.json").string();
        o.out_dir = path("over").string();
      },
      {"--out", "report.json", "the map"}, {path("over/report.json")},
      {path("over/path.csv"), path("over/path.png")});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  add("--out/path.png is a folder",
      [&](auto& o) { o.out_dir = path("png_is_a_folder").string(); }, {"--out", "is a folder"},
      {}, {path("png_is_a_folder/path.csv"), path("png_is_a_folder/report.json")});
  if (!root_) {
    add("--out in a read-only folder", [&](auto& o) { o.out_dir = path("locked/out").string(); },
        {"--out", "not writable"}, {}, {path("locked/out")});
  }
  EXPECT_GE(sweep("plan", rows), 15u);
}

TEST_F(CliSweepMaps, Topo) {
  const fs::path map = path("room.strata"), out = path("out");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what, const std::function<void(apps::TopoOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::TopoOptions o;
    o.map_path = map.string();
    o.radius_m = 0.2f;
    o.esdf_max_distance_m = 1.0f;
    o.out_dir = out.string();
    edit(o);
    unchanged.push_back(map);
    absent.push_back(out);
    rows.push_back({what, call(apps::runTopo, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("a negative radius", [](auto& o) { o.radius_m = -1.0f; }, {"--radius", ">= 0"});
  add("a NaN radius", [](auto& o) { o.radius_m = kNaN; }, {"--radius"});
  add("a radius the ESDF cannot hold", [](auto& o) { o.radius_m = 1.0f; },
      {"--radius", "--esdf-max-distance"});
  add("a zero ESDF distance", [](auto& o) { o.esdf_max_distance_m = 0.0f; },
      {"--esdf-max-distance"});
  add("an unknown policy", [](auto& o) { o.unknown = "sometimes"; }, {"--unknown"});
  add("an infinite slice height",
      [](auto& o) { o.slice_z_m = std::numeric_limits<float>::infinity(); }, {"--slice-z"});
  add("no --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("a missing map", [&](auto& o) { o.map_path = path("missing.strata").string(); },
      {"missing.strata"});
  add("a map that is not a map", [&](auto& o) { o.map_path = path("not_a_map.strata").string(); },
      {"not_a_map.strata"}, {path("not_a_map.strata")});
  add("--out is the map", [&](auto& o) { o.out_dir = map.string(); }, {"--out", "room.strata"});
  add("--out/topo.json is the map",
      [&](auto& o) {
        o.map_path = path("over/topo.json").string();
        o.out_dir = path("over").string();
      },
      {"--out", "topo.json"}, {path("over/topo.json")}, {path("over/topo.png")});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  EXPECT_GE(sweep("topo", rows), 12u);
}

TEST_F(CliSweepMaps, Explore) {
  const fs::path world = path("not_a_world.yaml"), out = path("out");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what,
                       const std::function<void(apps::ExploreOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::ExploreOptions o;
    o.world_path = world.string();
    o.out_dir = out.string();
    o.quiet = true;
    edit(o);
    unchanged.push_back(world);
    absent.push_back(out);
    rows.push_back({what, call(apps::runExplore, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("an unknown planner", [](auto& o) { o.planner = "frontier"; },
      {"--planner", "history or nbvp"});
  add("a negative time limit", [](auto& o) { o.time_limit_s = -5.0; }, {"--time-limit", "> 0"});
  add("a NaN voxel", [](auto& o) { o.voxel_size_m = kNaN; }, {"--voxel", "0.001 to 1"});
  add("a zero-width camera", [](auto& o) { o.camera_width_px = 0; }, {"--width", "8 to 8192"});
  add("a negative camera height", [](auto& o) { o.camera_height_px = -120; }, {"--height"});
  add("a zero evaluation period", [](auto& o) { o.eval_period_s = 0.0; }, {"--eval-period"});
  add("an infinite start yaw", [](auto& o) { o.start_yaw_deg = kInf; }, {"--start-yaw"});
  add("a NaN start", [](auto& o) { o.start = "2.5,2,nan"; }, {"--start"});
  add("a flat tree box", [](auto& o) { o.tree_box = "4,4,0"; }, {"--tree-box"});
  add("a mouth without a dead end", [](auto& o) { o.dead_end_mouth = "1,1"; },
      {"--dead-end-mouth"});
  add("a dead end inside out", [](auto& o) { o.dead_end = "5,5,1,1"; }, {"--dead-end"});
  add("no --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("a missing world", [&](auto& o) { o.world_path = path("missing.yaml").string(); },
      {"missing.yaml"});
  add("a world file that is not a world", [](auto&) {}, {"not_a_world.yaml"});
  add("--out is the world file", [&](auto& o) { o.out_dir = world.string(); },
      {"--out", "not_a_world.yaml"});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  add("--out/report.json is the world file",
      [&](auto& o) {
        o.world_path = path("over/report.json").string();
        o.out_dir = path("over").string();
      },
      {"--out", "report.json"}, {path("over/report.json")},
      {path("over/curve.png"), path("over/history")});
  EXPECT_GE(sweep("explore", rows), 17u);
}

TEST_F(CliSweepMaps, Align) {
  const fs::path out = path("out"), empty = path("empty.sqlite");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what, const std::function<void(apps::AlignOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::AlignOptions o;
    o.session_dirs = {path("gt_only").string()};
    o.out_dir = out.string();
    o.quiet = true;
    edit(o);
    unchanged.push_back(path("gt_only/groundtruth.txt"));
    unchanged.push_back(empty);
    absent.push_back(out);
    rows.push_back({what, call(apps::runAlign, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("--threads 0", [](auto& o) { o.threads = 0; }, {"--threads", "1 to 1024", "not 0"});
  add("--candidates 0", [](auto& o) { o.candidates = 0; }, {"--candidates", "1 to 1000"});
  add("a negative keyframe count", [](auto& o) { o.keyframe_every = -1; },
      {"--keyframe-every", "not -1"});
  add("both keyframe rules off", [](auto& o) { o.keyframe_every = 0; },
      {"--keyframe-every", "--keyframe-distance-m"});
  add("a NaN keyframe distance", [](auto& o) { o.keyframe_distance_m = NAN; },
      {"--keyframe-distance-m"});
  add("a NaN odometry sigma", [](auto& o) { o.odometry_sigma_m = NAN; }, {"--odometry-sigma-m"});
  add("a zero odometry sigma", [](auto& o) { o.odometry_sigma_rad = 0.0; },
      {"--odometry-sigma-rad", "> 0"});
  add("a negative loop gap", [](auto& o) { o.intra_gap_s = -1.0; }, {"--intra-gap-s"});
  add("folders without --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("neither folders nor --db", [](auto& o) { o.session_dirs.clear(), o.out_dir.clear(); },
      {"--db"});
  add("a missing session folder",
      [&](auto& o) { o.session_dirs.push_back(path("no_such_session").string()); },
      {"no_such_session", "does not exist"});
  add("a session folder that is a file",
      [&](auto& o) { o.session_dirs = {path("a_file.txt").string()}; }, {"a_file.txt"});
  add("a missing --db", [&](auto& o) {
        o.session_dirs.clear();
        o.db_path = path("absent.sqlite").string();
      },
      {"absent.sqlite", "does not exist"}, {}, {path("absent.sqlite")});
  add("a --db that is not a map", [&](auto& o) {
        o.session_dirs.clear();
        o.db_path = path("not_a_db.sqlite").string();
        o.out_dir.clear();
      },
      {"not_a_db.sqlite"}, {path("not_a_db.sqlite")});
  add("--out is the session folder", [&](auto& o) { o.out_dir = path("gt_only").string(); },
      {"--out", "gt_only", "same folder"}, {}, {path("gt_only/map.sqlite")});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  add("--db is the report the run writes beside it", [&](auto& o) {
        o.session_dirs.clear();
        o.out_dir.clear();
        o.db_path = path("db_out/report.json").string();
      },
      {"--out", "report.json"}, {path("db_out/report.json")}, {path("db_out/loops.csv")});
  add("a new --db named as an output in a new --out",
      [&](auto& o) { o.db_path = (out / "loops.csv").string(); }, {"--db", "loops.csv"});
  // The failed session: imported, then refused by the alignment; the store keeps none of it.
  add("a session that cannot be aligned, into an existing map",
      [&](auto& o) { o.db_path = empty.string(); }, {"gt_only", "not a TUM RGB-D folder"});
  add("a session that cannot be aligned, into a new map", [](auto&) {},
      {"gt_only", "not a TUM RGB-D folder"});
  add("the next run on the map meets no half-made session", [&](auto& o) {
        o.session_dirs.clear();
        o.db_path = empty.string();
      },
      {"has no session"});
  EXPECT_GE(sweep("align", rows), 21u);
  store::Store db(empty.string());
  EXPECT_TRUE(db.sessions().empty()) << "the failed session stayed in the map";
}

TEST_F(CliSweepMaps, Objects) {
  const fs::path out = path("out");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what,
                       const std::function<void(apps::ObjectsOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::ObjectsOptions o;
    o.sessions = {path("session_a").string(), path("session_b").string()};
    o.out_dir = out.string();
    o.quiet = true;
    edit(o);
    unchanged.push_back(path("session_a/rgb.txt"));
    absent.push_back(out);
    rows.push_back({what, call(apps::runObjects, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("one session", [](auto& o) { o.sessions.pop_back(); }, {"at least two sessions"});
  add("a missing session", [&](auto& o) { o.sessions[1] = path("nowhere").string(); },
      {"nowhere", "does not exist"});
  add("a session that is a file", [&](auto& o) { o.sessions[1] = path("a_file.txt").string(); },
      {"a_file.txt", "a file"});
  add("--frames -1", [](auto& o) { o.frames = -1; }, {"--frames", "not -1"});
  add("a NaN voxel", [](auto& o) { o.voxel_size_m = kNaN; }, {"--voxel", "0.001 to 1"});
  add("a 5 m voxel", [](auto& o) { o.voxel_size_m = 5.0f; }, {"--voxel", "0.001 to 1"});
  add("a zero minimum weight", [](auto& o) { o.min_weight = 0.0f; }, {"--min-weight", "> 0"});
  add("no --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("--out is a session", [&](auto& o) { o.out_dir = o.sessions[0]; },
      {"--out", "session_a", "same folder"});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  add("--before-after in a missing folder",
      [&](auto& o) { o.before_after_png = path("nowhere/before_after.png").string(); },
      {"--before-after", "does not exist"});
  add("--before-after is the world file", [&](auto& o) {
        o.world = path("not_a_world.yaml").string();
        o.before_after_png = o.world;
      },
      {"--before-after", "--world"}, {path("not_a_world.yaml")});
  add("--before-after is one of the files in --out",
      [&](auto& o) { o.before_after_png = (out / "objects.png").string(); },
      {"--before-after", "objects.png"});
  EXPECT_GE(sweep("objects", rows), 13u);
}

TEST_F(CliSweepMaps, Diff) {
  const fs::path out = path("out"), room = path("room.strata"), coarse = path("coarse.strata");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what, const std::function<void(apps::DiffOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::DiffOptions o;
    o.sessions = {room.string(), room.string()};
    o.out_dir = out.string();
    o.quiet = true;
    edit(o);
    unchanged.push_back(room);
    unchanged.push_back(coarse);
    absent.push_back(out);
    rows.push_back({what, call(apps::runDiff, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("saved maps of different voxel sizes",
      [&](auto& o) { o.sessions = {room.string(), coarse.string()}; },
      {"room.strata", "coarse.strata", "voxel size 0.1", "voxel size 0.2"});
  add("a map that is not a map",
      [&](auto& o) { o.sessions[1] = path("not_a_map.strata").string(); },
      {"not_a_map.strata"}, {path("not_a_map.strata")});
  add("one session", [](auto& o) { o.sessions.pop_back(); }, {"at least two sessions"});
  add("a missing session", [&](auto& o) { o.sessions[0] = path("gone.strata").string(); },
      {"gone.strata", "does not exist"});
  add("--stride 0", [](auto& o) { o.stride = 0; }, {"--stride", "not 0"});
  add("--frames -3", [](auto& o) { o.frames = -3; }, {"--frames", "not -3"});
  add("a NaN voxel", [](auto& o) { o.voxel_size_m = kNaN; }, {"--voxel-size", "0.001 to 1"});
  add("a NaN minimum weight", [](auto& o) { o.min_weight = kNaN; }, {"--min-weight"});
  add("a threshold within the merge distance", [](auto& o) { o.difference_threshold_m = 0.01f; },
      {"--threshold", "> 0.02"});
  add("an unknown weight", [](auto& o) { o.weight = "inverse"; },
      {"--weight", "constant or inv-z2"});
  add("an unknown layout", [](auto& o) { o.dataset_options.format = "kitti"; },
      {"--format", "kitti"});
  add("a trajectory for a saved map",
      [&](auto& o) { o.trajectories = {path("a_file.txt").string(), path("a_file.txt").string()}; },
      {"saved map", "--trajectory"}, {path("a_file.txt")});
  add("one trajectory for two sessions",
      [&](auto& o) { o.trajectories = {path("a_file.txt").string()}; },
      {"--trajectory given 1 time(s) for 2 sessions"});
  add("no --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("--out is a saved map", [&](auto& o) { o.out_dir = room.string(); },
      {"--out", "room.strata"});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  add("--out/report.json is a trajectory", [&](auto& o) {
        o.sessions = {path("session_a").string(), path("session_b").string()};
        const std::string trajectory = path("trajectories/report.json").string();
        o.trajectories = {trajectory, trajectory};
        o.out_dir = path("trajectories").string();
      },
      {"--out", "--trajectory", "report.json"}, {path("trajectories/report.json")},
      {path("trajectories/static_mesh.ply")});
  add("--out is a session folder", [&](auto& o) {
        o.sessions = {path("session_a").string(), path("session_b").string()};
        o.out_dir = o.sessions[0];
      },
      {"--out", "same folder"}, {path("session_a/rgb.txt")}, {path("session_a/report.json")});
  EXPECT_GE(sweep("diff", rows), 18u);
}

TEST_F(CliSweepMaps, Select) {
  const fs::path out = path("out"), map = path("room.strata");
  std::vector<Row> rows;
  const auto add = [&](const std::string& what,
                       const std::function<void(apps::SelectOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::SelectOptions o;
    o.map_path = map.string();
    o.session_dir = path("session_a").string();
    o.out_dir = out.string();
    o.quiet = true;
    edit(o);
    unchanged.push_back(map);
    unchanged.push_back(path("session_a/rgb.txt"));
    absent.push_back(out);
    rows.push_back({what, call(apps::runSelect, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("--stride 0", [](auto& o) { o.stride_px = 0; }, {"--stride", "1 to 4096"});
  add("an even window", [](auto& o) { o.window = 4; }, {"--window", "odd"});
  add("a negative dilation", [](auto& o) { o.dilation = -1; }, {"--dilation", "not -1"});
  add("--frames -1", [](auto& o) { o.frames = -1; }, {"--frames"});
  add("an unknown method", [](auto& o) { o.method = "sift"; },
      {"--method", "sift", "reproj, ncc or hist"});
  add("a NaN coverage threshold", [](auto& o) { o.coverage_threshold = NAN; },
      {"--coverage-threshold", "finite"});
  add("an infinite depth threshold", [](auto& o) { o.depth_threshold_m = kInf; },
      {"--depth-threshold"});
  add("an empty --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  add("a missing map", [&](auto& o) { o.map_path = path("missing.strata").string(); },
      {"missing.strata"});
  add("a map that is not a map", [&](auto& o) { o.map_path = path("not_a_map.strata").string(); },
      {"not_a_map.strata"}, {path("not_a_map.strata")});
  add("a missing session", [&](auto& o) { o.session_dir = path("nowhere").string(); },
      {"nowhere", "does not exist"});
  add("a missing calibration session",
      [&](auto& o) { o.calibrate_dir = path("nowhere").string(); }, {"--calibrate", "nowhere"});
  add("--out is the map", [&](auto& o) { o.out_dir = map.string(); }, {"--out", "room.strata"});
  add("--out is the session", [&](auto& o) { o.out_dir = o.session_dir; },
      {"--out", "same folder"}, {}, {path("session_a/keyframes.csv")});
  add("--out/keyframes.csv is the map",
      [&](auto& o) {
        o.map_path = path("over/keyframes.csv").string();
        o.out_dir = path("over").string();
      },
      {"--out", "keyframes.csv"}, {path("over/keyframes.csv")}, {path("over/selection.png")});
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  EXPECT_GE(sweep("select", rows), 16u);
}

TEST_F(CliSweepMaps, Demo) {
  std::vector<Row> rows;
  const auto add = [&](const std::string& what, const std::function<void(apps::DemoOptions&)>& edit,
                       std::vector<std::string> words, std::vector<fs::path> unchanged = {},
                       std::vector<fs::path> absent = {}) {
    apps::DemoOptions o;
    o.quiet = true;
    edit(o);
    rows.push_back({what, call(apps::runDemo, o), 2, std::move(words), std::move(unchanged),
                    std::move(absent)});
  };
  add("--out is a file", [&](auto& o) { o.out_dir = path("a_file.txt").string(); },
      {"--out", "not a folder"}, {path("a_file.txt")});
  add("--out is the world file", [&](auto& o) {
        o.world = path("not_a_world.yaml").string();
        o.out_dir = o.world;
      },
      {"--out", "not_a_world.yaml"}, {path("not_a_world.yaml")});
  add("an empty --out", [](auto& o) { o.out_dir.clear(); }, {"--out"});
  if (!root_) {
    add("--out in a read-only folder", [&](auto& o) { o.out_dir = path("locked/out").string(); },
        {"--out", "not writable"}, {}, {path("locked/out")});
  }
  EXPECT_GE(sweep("demo", rows), 3u);
}

// The parser's own checks name the accepted range in plain numbers (not "0.000000 to
// 1797693..."), and a NaN where a number is due.
TEST(CliSweepMapsParser, RangesInPlainNumbers) {
  struct Case {
    std::string line;
    std::vector<std::string> words;
  };
  const std::vector<Case> cases = {
      {"align --db m.sqlite --threads 0", {"--threads", "1 to 1024"}},
      {"align --db m.sqlite --candidates 0", {"--candidates", "1 to 1000"}},
      {"align --db m.sqlite --odometry-sigma-m nan", {"--odometry-sigma-m", "not a finite"}},
      {"plan m.strata --from 0,0,0 --to 1,1,1 --out o --planner dijkstra",
       {"--planner", "dijkstra"}},
      {"plan m.strata --from 0,0,0 --to 1,1,1 --out o --radius nan", {"--radius", "not a finite"}},
      {"topo m.strata --out o --slice-z inf", {"--slice-z", "not a finite"}},
      {"diff a b --out o --stride 0", {"--stride", "not in range 1 to"}},
      {"diff a b --out o --frames -1", {"--frames", "not in range 0 to"}},
      {"select m.strata s --stride 0", {"--stride", "1 to 4096"}},
      {"select m.strata s --window 0", {"--window"}},
      {"explore w.yaml --out o --width 0", {"--width", "8 to 8192"}},
      {"explore w.yaml --out o --voxel nan", {"--voxel", "not a finite"}},
      {"objects a b --out o --frames -2", {"--frames", "not in range 0 to"}},
  };
  for (const Case& c : cases) {
    CLI::App app{"strata"};
    apps::AlignOptions align;
    apps::addAlignCommand(app, align);
    apps::PlanOptions plan;
    apps::addPlanCommand(app, plan);
    apps::TopoOptions topo;
    apps::addTopoCommand(app, topo);
    apps::DiffOptions diff;
    apps::addDiffCommand(app, diff);
    apps::SelectOptions select;
    apps::addSelectCommand(app, select);
    apps::ExploreOptions explore;
    apps::addExploreCommand(app, explore);
    apps::ObjectsOptions objects;
    apps::addObjectsCommand(app, objects);
    std::string message;
    try {
      app.parse(c.line, false);
    } catch (const CLI::ParseError& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << c.line << ": parsed";
    for (const std::string& word : c.words) {
      EXPECT_NE(message.find(word), std::string::npos) << c.line << ": " << message;
    }
    EXPECT_EQ(message.find("1797693"), std::string::npos) << c.line << ": " << message;
  }
}

}  // namespace
}  // namespace strata
