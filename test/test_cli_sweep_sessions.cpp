// Bad input to the session commands (`strata odometry`, `eval-trajectory`, `sim`, `drift`, `fuse`,
// `mesh`, `esdf`), run in-process: each row names the options, the exit code (2: bad input), the
// words the message must hold, the inputs that must stay byte for byte as they were and the
// outputs that must not exist afterwards. Every row must fail before any work: the inputs of the
// fixture are skeletons (a session whose files are not EuRoC files, a map that is not a map, a
// world file with an error on line 4), so a command that read them before checking its options
// and outputs would fail with another message. Besides each row's own columns, no row may change
// anything in the fixture's folder (no file written, no folder made).
// With the shared EuRoC excerpt: a session that never tracks exits 3 without a trajectory, and a
// session without cam1 is refused unless --mono is given.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/drift_command.h"
#include "cli/esdf_command.h"
#include "cli/eval_trajectory_command.h"
#include "cli/fuse_command.h"
#include "cli/mesh_command.h"
#include "cli/odometry_command.h"
#include "cli/sim_command.h"
#include "strata/core/types.h"
#include "strata/io/image_io.h"
#include "cli_sweep.h"
#include "test_utils.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

using Row = test::SweepRow;
using test::writeText;

/// A TUM trajectory: `count` poses from `t0_s` every 0.1 s along x.
std::string tumTrajectory(double t0_s, int count) {
  std::ostringstream s;
  s << "# timestamp tx ty tz qx qy qz qw\n";
  for (int i = 0; i < count; ++i) {
    s << t0_s + 0.1 * i << " " << 0.1 * i << " " << 0.02 * i * i << " 0 0 0 0 1\n";
  }
  return s.str();
}

class CliSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::freshTempDir("cli_sweep_sessions");
    // A session skeleton in the EuRoC layout whose files are not EuRoC files: read, they fail.
    for (const char* file : {"mav0/cam0/sensor.yaml", "mav0/cam0/data.csv",
                             "mav0/cam1/sensor.yaml", "mav0/cam1/data.csv",
                             "mav0/imu0/sensor.yaml", "mav0/imu0/data.csv"}) {
      writeText(path("session") / file, std::string("not read: ") + file + "\n");
      if (std::string(file).rfind("mav0/cam1", 0) != 0) {
        writeText(path("mono_session") / file, std::string("not read: ") + file + "\n");
      }
    }
    writeText(path("session/groundtruth_body.txt"), "not read\n");
    // Trajectories: 10 poses each, matching in time; one of 3 poses of which 2 match; an empty one.
    writeText(path("est.txt"), tumTrajectory(0.0, 10));
    writeText(path("gt.txt"), tumTrajectory(0.0, 10));
    writeText(path("two_match.txt"), tumTrajectory(0.0, 2) + "50.0 0 0 0 0 0 0 1\n");
    writeText(path("far.txt"), tumTrajectory(100.0, 10));
    writeText(path("empty.txt"), "# timestamp tx ty tz qx qy qz qw\n");
    writeText(path("malformed.txt"), "0.0 1 2 3\n");
    // A "map" that is not a map, a world file with an error on line 4, a TUM source skeleton.
    writeText(path("map.strata"), "not a Strata map\n");
    writeText(path("world.yaml"),
              "name: bad\nseed: 1\nrooms:\n  - {name: r, min: [0, 0], max: [4]}\n");
    writeText(path("tum/depth.txt"), "one-field\n");
    writeText(path("tum/rgb.txt"), "not read\n");
    writeText(path("tum/groundtruth.txt"), "not read\n");
    writeText(path("camera.yaml"), "not read\n");
    test::makeCommonFixtures(dir_);
  }

  void TearDown() override { test::removeFixtures(dir_); }

  fs::path path(const std::string& name) const { return dir_ / name; }
  std::string str(const std::string& name) const { return path(name).string(); }

  void sweep(const std::vector<Row>& rows) {
    test::sweepRows("session commands", rows, dir_);
  }

  // The commands with the fixture's defaults, edited by a row.
  std::function<int()> odometry(std::function<void(apps::OdometryOptions&)> edit) const {
    apps::OdometryOptions o;
    o.session_dir = str("session");
    o.out_path = str("traj.txt");
    o.quiet = true;
    edit(o);
    return [o] { return apps::runOdometry(o); };
  }
  std::function<int()> evalTrajectory(
      std::function<void(apps::EvalTrajectoryOptions&)> edit) const {
    apps::EvalTrajectoryOptions o;
    o.estimate_path = str("est.txt");
    o.truth_path = str("gt.txt");
    o.json_path = str("ate.json");
    edit(o);
    return [o] { return apps::runEvalTrajectory(o); };
  }
  std::function<int()> sim(std::function<void(apps::SimOptions&)> edit) const {
    apps::SimOptions o;
    o.world = str("world.yaml");
    o.out_dir = str("sim_out");
    o.quiet = true;
    edit(o);
    return [o] { return apps::runSim(o); };
  }
  std::function<int()> drift(std::function<void(apps::DriftOptions&)> edit) const {
    apps::DriftOptions o;
    o.source_dir = str("tum");
    o.out_dir = str("drift_out");
    edit(o);
    return [o] { return apps::runDrift(o); };
  }
  std::function<int()> fuse(std::function<void(apps::FuseOptions&)> edit) const {
    apps::FuseOptions o;  // the built-in analytic scene unless a row names a dataset
    o.map_path = str("fused.strata");
    o.quiet = true;
    edit(o);
    return [o] { return apps::runFuse(o); };
  }
  std::function<int()> mesh(std::function<void(apps::MeshOptions&)> edit) const {
    apps::MeshOptions o;
    o.map_path = str("map.strata");
    o.out_path = str("mesh.ply");
    edit(o);
    return [o] { return apps::runMesh(o); };
  }
  std::function<int()> esdf(std::function<void(apps::EsdfOptions&)> edit) const {
    apps::EsdfOptions o;
    o.map_path = str("map.strata");
    o.png_path = str("slice.png");
    edit(o);
    return [o] { return apps::runEsdf(o); };
  }

  fs::path dir_;
};

TEST_F(CliSweep, Odometry) {
  const fs::path session = path("session");
  const fs::path imu = path("session/mav0/imu0/data.csv");
  const fs::path traj = path("traj.txt"), summary = path("traj.json");
  sweep({
      {"--window 1", odometry([](auto& o) { o.window = 1; }), 2,
       {"--window", "at least 2"}, {session}, {traj, summary}},
      {"--features -5", odometry([](auto& o) { o.max_features = -5; }), 2,
       {"--features", ">= 0"}, {session}, {traj, summary}},
      {"--frames -5", odometry([](auto& o) { o.frames = -5; }), 2,
       {"--frames", ">= 0"}, {session}, {traj, summary}},
      {"--mode rgbd", odometry([](auto& o) { o.mode = "rgbd"; }), 2,
       {"--mode rgbd", "vio"}, {session}, {traj, summary}},
      {"--out t.json: the default summary is the trajectory itself",
       odometry([&](auto& o) { o.out_path = str("t.json"); }), 2,
       {"--summary (default: --out with .json)", "same file as the output --out", "t.json"},
       {session}, {path("t.json")}},
      {"--out over the IMU file the run reads",
       odometry([&](auto& o) { o.out_path = imu.string(); }), 2,
       {"--out", "would overwrite a file of the input", "mav0"}, {session, imu},
       {path("session/mav0/imu0/data.json")}},
      {"--summary over the session's groundtruth_body.txt",
       odometry([&](auto& o) { o.summary_path = str("session/groundtruth_body.txt"); }), 2,
       {"--summary", "same file as the input", "groundtruth_body.txt"}, {session},
       {traj}},
      {"--plot is --out", odometry([&](auto& o) { o.plot_path = str("traj.txt"); }), 2,
       {"--plot", "same file as the output --out"}, {session}, {traj, summary}},
      {"--frames-csv is --summary",
       odometry([&](auto& o) {
         o.summary_path = str("s.json");
         o.frames_csv_path = str("s.json");
       }),
       2, {"--frames-csv", "same file as the output --summary"}, {session},
       {traj, path("s.json")}},
      {"--out in a folder that does not exist",
       odometry([&](auto& o) { o.out_path = str("no_such_folder/t.txt"); }), 2,
       {"--out", "no_such_folder", "does not exist"}, {session},
       {path("no_such_folder")}},
      {"--out is a folder", odometry([&](auto& o) { o.out_path = str("a_folder"); }), 2,
       {"--out", "is a folder, not a file"}, {session, path("a_folder")},
       {path("a_folder.json")}},
      {"--out below a file", odometry([&](auto& o) { o.out_path = str("a_file/t.txt"); }), 2,
       {"--out", "is not a folder"}, {session, path("a_file")}, {}},
      {"--out in a read-only folder",
       odometry([&](auto& o) { o.out_path = str("readonly/t.txt"); }), 2,
       {"--out", "is not writable"}, {session}, {path("readonly/t.txt"), path("readonly/t.json")},
       true},
      {"a session without cam1 is not run as mono without --mono",
       odometry([&](auto& o) { o.session_dir = str("mono_session"); }), 2,
       {"cam1", "--mono"}, {path("mono_session")}, {traj, summary}},
      {"a session folder that does not exist",
       odometry([&](auto& o) { o.session_dir = str("no_such_session"); }), 2,
       {"no_such_session", "EuRoC session folder not found"}, {}, {traj, summary}},
      {"a session whose files are not EuRoC files (--mono: read)",
       odometry([&](auto& o) {
         o.session_dir = str("mono_session");
         o.mono = true;
       }),
       2, {"mono_session"}, {path("mono_session")}, {traj, summary}},
  });
}

TEST_F(CliSweep, EvalTrajectory) {
  const fs::path est = path("est.txt"), gt = path("gt.txt"), json = path("ate.json");
  sweep({
      {"--json over the truth", evalTrajectory([&](auto& o) { o.json_path = gt.string(); }), 2,
       {"--json", "same file as the input the true trajectory"}, {est, gt}, {}},
      {"--json over the estimate",
       evalTrajectory([&](auto& o) { o.json_path = est.string(); }), 2,
       {"--json", "same file as the input the estimated trajectory"}, {est, gt}, {}},
      {"--json over the truth by another spelling",
       evalTrajectory(
           [&](auto& o) { o.json_path = (dir_ / "a_folder" / ".." / "gt.txt").string(); }),
       2, {"--json", "the true trajectory"}, {est, gt}, {}},
      {"--plot is --json", evalTrajectory([&](auto& o) { o.plot_path = json.string(); }), 2,
       {"--plot", "same file as the output --json"}, {est, gt}, {json}},
      {"--json in a folder that does not exist",
       evalTrajectory([&](auto& o) { o.json_path = str("no_such_folder/ate.json"); }), 2,
       {"--json", "does not exist"}, {est, gt}, {path("no_such_folder")}},
      {"--json is a folder", evalTrajectory([&](auto& o) { o.json_path = str("a_folder"); }), 2,
       {"--json", "is a folder, not a file"}, {est, gt, path("a_folder")}, {}},
      {"--plot in a read-only folder",
       evalTrajectory([&](auto& o) { o.plot_path = str("readonly/ate.png"); }), 2,
       {"--plot", "is not writable"}, {est, gt}, {json, path("readonly/ate.png")}, true},
      {"--align sim4", evalTrajectory([](auto& o) { o.alignment = "sim4"; }), 2,
       {"sim4", "none, first, se3 or sim3"}, {est, gt}, {json}},
      {"--max-dt nan", evalTrajectory([](auto& o) { o.max_time_difference_s = std::nan(""); }),
       2, {"--max-dt", "finite"}, {est, gt}, {json}},
      {"--max-dt -1", evalTrajectory([](auto& o) { o.max_time_difference_s = -1.0; }), 2,
       {"--max-dt", ">= 0"}, {est, gt}, {json}},
      {"--segment 0", evalTrajectory([](auto& o) { o.rpe_segment_m = 0.0; }), 2,
       {"--segment", "> 0"}, {est, gt}, {json}},
      {"--segment inf",
       evalTrajectory([](auto& o) { o.rpe_segment_m = std::numeric_limits<double>::infinity(); }),
       2, {"--segment", "finite"}, {est, gt}, {json}},
      {"an empty estimate says it is empty",
       evalTrajectory([&](auto& o) { o.estimate_path = str("empty.txt"); }), 2,
       {"empty.txt", "estimated trajectory is empty"}, {path("empty.txt"), gt}, {json}},
      {"an empty truth says it is empty",
       evalTrajectory([&](auto& o) { o.truth_path = str("empty.txt"); }), 2,
       {"empty.txt", "true trajectory is empty"}, {est, path("empty.txt")}, {json}},
      {"2 associated poses are too few for an ATE",
       evalTrajectory([&](auto& o) { o.estimate_path = str("two_match.txt"); }), 2,
       {"2 of the 3 estimated poses", "at least 3"}, {path("two_match.txt"), gt}, {json}},
      {"no associated pose",
       evalTrajectory([&](auto& o) { o.estimate_path = str("far.txt"); }), 2,
       {"0 of the 10 estimated poses", "--max-dt"}, {path("far.txt"), gt}, {json}},
      {"--max-dt 0 with timestamps apart",
       evalTrajectory([&](auto& o) {
         o.truth_path = str("far.txt");
         o.max_time_difference_s = 0.0;
       }),
       2, {"0 of the 10"}, {est, path("far.txt")}, {json}},
      {"a missing estimate", evalTrajectory([&](auto& o) { o.estimate_path = str("nope.txt"); }),
       2, {"nope.txt", "not found"}, {gt}, {json}},
      {"an estimate that is a folder",
       evalTrajectory([&](auto& o) { o.estimate_path = str("a_folder"); }), 2,
       {"a_folder", "not a regular file"}, {gt}, {json}},
      {"a malformed estimate line",
       evalTrajectory([&](auto& o) { o.estimate_path = str("malformed.txt"); }), 2,
       {"malformed.txt", "expected 'timestamp tx ty tz qx qy qz qw'"}, {gt}, {json}},
  });
}

TEST_F(CliSweep, Sim) {
  const fs::path world = path("world.yaml"), out = path("sim_out");
  sweep({
      {"--sessions -1", sim([](auto& o) { o.sessions = -1; }), 2, {"--sessions", "0..1000"},
       {world}, {out}},
      {"--sessions 1001", sim([](auto& o) { o.sessions = 1001; }), 2, {"--sessions"}, {world},
       {out}},
      {"--frames -5", sim([](auto& o) { o.max_frames = -5; }), 2,
       {"--frames", "0 (every frame) or at least 2"}, {world}, {out}},
      {"--frames 1", sim([](auto& o) { o.max_frames = 1; }), 2, {"--frames", "at least 2"},
       {world}, {out}},
      {"--rate 0", sim([](auto& o) { o.rate_hz = 0.0; }), 2, {"--rate", "> 0"}, {world}, {out}},
      {"--rate nan", sim([](auto& o) { o.rate_hz = std::nan(""); }), 2, {"--rate", "finite"},
       {world}, {out}},
      {"--rest -1", sim([](auto& o) { o.rest_s = -1.0; }), 2, {"--rest", ">= 0"}, {world}, {out}},
      {"--stereo-duration nan",
       sim([](auto& o) {
         o.stereo = true;
         o.stereo_duration_s = std::nan("");
       }),
       2, {"--stereo-duration", "finite"}, {world}, {out}},
      {"--stereo-width 0",
       sim([](auto& o) {
         o.stereo = true;
         o.stereo_width_px = 0;
       }),
       2, {"--stereo-width", "8..16384"}, {world}, {out}},
      {"--stereo-height -480", sim([](auto& o) { o.stereo_height_px = -480; }), 2,
       {"--stereo-height", "8..16384"}, {world}, {out}},
      {"--exposure-gain-sigma 0.7",
       sim([](auto& o) {
         o.stereo = true;
         o.exposure_gain_sigma = 0.7;
       }),
       2, {"--exposure-gain-sigma", "[0, 0.5)"}, {world}, {out}},
      {"--exposure-offset-sigma inf",
       sim([](auto& o) { o.exposure_offset_sigma = std::numeric_limits<double>::infinity(); }),
       2, {"--exposure-offset-sigma", "finite"}, {world}, {out}},
      {"--mono without --stereo", sim([](auto& o) { o.mono = true; }), 2,
       {"--mono needs --stereo"}, {world}, {out}},
      {"--out is the world file", sim([&](auto& o) { o.out_dir = world.string(); }), 2,
       {"--out", "world.yaml", "is not a folder"}, {world}, {}},
      {"--out is a file", sim([&](auto& o) { o.out_dir = str("a_file"); }), 2,
       {"--out", "is not a folder"}, {world, path("a_file")}, {}},
      {"--out below a file", sim([&](auto& o) { o.out_dir = str("a_file/out"); }), 2,
       {"--out", "is not a folder"}, {world, path("a_file")}, {}},
      {"--out in a read-only folder", sim([&](auto& o) { o.out_dir = str("readonly/out"); }), 2,
       {"--out", "is not writable"}, {world}, {path("readonly/out")}, true},
      {"a missing world file", sim([&](auto& o) { o.world = str("nope.yaml"); }), 2,
       {"cannot open world file", "nope.yaml"}, {}, {out}},
      {"a world file with an error: read, refused, nothing made", sim([](auto&) {}), 2,
       {"world.yaml", ":4:"}, {world}, {out}},
  });
}

TEST_F(CliSweep, Drift) {
  const fs::path source = path("tum"), out = path("drift_out");
  sweep({
      {"--out is the source", drift([&](auto& o) { o.out_dir = source.string(); }), 2,
       {"--out", "same folder as the input the source folder"}, {source}, {}},
      {"--out is the source by another spelling",
       drift([&](auto& o) { o.out_dir = (source / ".." / "tum" / "").string(); }), 2,
       {"--out", "the source folder"}, {source}, {}},
      {"--out is a file", drift([&](auto& o) { o.out_dir = str("a_file"); }), 2,
       {"--out", "is not a folder"}, {source, path("a_file")}, {}},
      {"--out in a read-only folder", drift([&](auto& o) { o.out_dir = str("readonly/out"); }),
       2, {"--out", "is not writable"}, {source}, {path("readonly/out")}, true},
      {"--last -5", drift([](auto& o) { o.last_frame = -5; }), 2, {"--last", ">= 0"}, {source},
       {out}},
      {"--first 4 --last 2",
       drift([](auto& o) {
         o.first_frame = 4;
         o.last_frame = 2;
       }),
       2, {"first_frame 4 is after last_frame 2"}, {source}, {out}},
      {"--translation-sigma nan",
       drift([](auto& o) { o.config.drift.translation_sigma_m_per_sqrt_m = std::nan(""); }), 2,
       {"--translation-sigma", "finite"}, {source}, {out}},
      {"--yaw-sigma -1", drift([](auto& o) { o.config.drift.yaw_sigma_rad_per_sqrt_m = -1.0; }),
       2, {"--yaw-sigma", ">= 0"}, {source}, {out}},
      {"--offset-translation-m inf",
       drift([](auto& o) {
         o.config.frame.horizontal_offset_m = std::numeric_limits<double>::infinity();
       }),
       2, {"--offset-translation-m", "finite"}, {source}, {out}},
      {"a missing source", drift([&](auto& o) { o.source_dir = str("nope"); }), 2,
       {"nope: no such folder"}, {}, {out}},
      {"a source that is a file", drift([&](auto& o) { o.source_dir = str("a_file"); }), 2,
       {"a_file: not a folder"}, {path("a_file")}, {out}},
      {"a malformed source list: read, refused, --out not made", drift([](auto&) {}), 2,
       {"depth.txt", "expected 'timestamp filename'"}, {source}, {out}},
  });
}

TEST_F(CliSweep, Fuse) {
  const fs::path map = path("fused.strata");
  sweep({
      {"--voxel-size nan", fuse([](auto& o) { o.map.voxel_size_m = std::nanf(""); }), 2,
       {"--voxel-size", "0.001 to 1"}, {}, {map}},
      {"--voxel-size 0", fuse([](auto& o) { o.map.voxel_size_m = 0.0f; }), 2,
       {"--voxel-size", "0.001 to 1"}, {}, {map}},
      {"--truncation -1", fuse([](auto& o) { o.truncation_m = -1.0f; }), 2,
       {"--truncation", ">= 0"}, {}, {map}},
      {"--truncation nan", fuse([](auto& o) { o.truncation_m = std::nanf(""); }), 2,
       {"--truncation", "finite"}, {}, {map}},
      {"--truncation under one voxel", fuse([](auto& o) { o.truncation_m = 0.001f; }), 2,
       {"--truncation", "under one voxel"}, {}, {map}},
      {"--max-weight 0", fuse([](auto& o) { o.map.max_weight = 0.0f; }), 2,
       {"--max-weight", "> 0"}, {}, {map}},
      {"--min-depth above --max-depth",
       fuse([](auto& o) {
         o.map.min_depth_m = 3.0f;
         o.map.max_depth_m = 2.0f;
       }),
       2, {"--min-depth", "below --max-depth"}, {}, {map}},
      {"--max-depth inf",
       fuse([](auto& o) { o.map.max_depth_m = std::numeric_limits<float>::infinity(); }), 2,
       {"--max-depth", "finite"}, {}, {map}},
      {"--frames -5", fuse([](auto& o) { o.frames = -5; }), 2, {"--frames", ">= 0"}, {}, {map}},
      {"--stride 0", fuse([](auto& o) { o.stride = 0; }), 2, {"--stride", "at least 1"}, {},
       {map}},
      {"--slice-z nan", fuse([](auto& o) { o.slice_z_m = std::nanf(""); }), 2,
       {"--slice-z", "finite"}, {}, {map}},
      {"--depth-scale 0", fuse([](auto& o) { o.dataset_options.depth_scale = 0.0; }), 2,
       {"--depth-scale", "> 0"}, {}, {map}},
      {"--weight unknown", fuse([](auto& o) { o.weight = "heavy"; }), 2,
       {"--weight heavy", "constant or inv-z2"}, {}, {map}},
      {"--distance unknown", fuse([](auto& o) { o.distance = "sideways"; }), 2,
       {"--distance sideways", "point-to-plane or along-ray"}, {}, {map}},
      {"--format unknown",
       fuse([&](auto& o) {
         o.dataset = str("tum");
         o.dataset_options.format = "kitti";
       }),
       2, {"--format kitti", "auto, tum or 7scenes"}, {path("tum")}, {map}},
      {"--esdf-png with --reference",
       fuse([&](auto& o) {
         o.esdf_png_path = str("slice.png");
         o.reference = true;
       }),
       2, {"--esdf-png", "drop --reference"}, {}, {map, path("slice.png")}},
      {"--trajectory without --track",
       fuse([&](auto& o) { o.trajectory_path = str("track.txt"); }), 2,
       {"--trajectory needs --track"}, {}, {map, path("track.txt")}},
      {"--mesh is --map", fuse([&](auto& o) { o.mesh_path = map.string(); }), 2,
       {"--mesh", "same file as the output --map"}, {}, {map}},
      {"--map over the dataset's groundtruth.txt",
       fuse([&](auto& o) {
         o.dataset = str("tum");
         o.map_path = str("tum/groundtruth.txt");
       }),
       2, {"--map", "would overwrite a file of the input the dataset folder"}, {path("tum")}, {}},
      {"--mesh over --camera",
       fuse([&](auto& o) {
         o.dataset_options.camera_file = str("camera.yaml");
         o.mesh_path = str("camera.yaml");
       }),
       2, {"--mesh", "same file as the input --camera"}, {path("camera.yaml")}, {map}},
      {"--map in a folder that does not exist",
       fuse([&](auto& o) { o.map_path = str("no_such_folder/m.strata"); }), 2,
       {"--map", "does not exist"}, {}, {path("no_such_folder")}},
      {"--render is a folder", fuse([&](auto& o) { o.render_path = str("a_folder"); }), 2,
       {"--render", "is a folder, not a file"}, {path("a_folder")}, {map}},
      {"--map in a read-only folder",
       fuse([&](auto& o) { o.map_path = str("readonly/m.strata"); }), 2,
       {"--map", "is not writable"}, {}, {path("readonly/m.strata")}, true},
      {"a dataset folder that does not exist",
       fuse([&](auto& o) { o.dataset = str("no_such_dataset"); }), 2, {"no_such_dataset"}, {},
       {map}},
  });
}

TEST_F(CliSweep, Mesh) {
  const fs::path map = path("map.strata"), ply = path("mesh.ply");
  sweep({
      {"--out over the map", mesh([&](auto& o) { o.out_path = map.string(); }), 2,
       {"--out", "same file as the input the map"}, {map}, {}},
      {"--out over the map by another spelling",
       mesh([&](auto& o) { o.out_path = (dir_ / "." / "map.strata").string(); }), 2,
       {"--out", "the map"}, {map}, {}},
      {"--out is a folder", mesh([&](auto& o) { o.out_path = str("a_folder"); }), 2,
       {"--out", "is a folder, not a file"}, {map, path("a_folder")}, {}},
      {"--out in a folder that does not exist",
       mesh([&](auto& o) { o.out_path = str("no_such_folder/m.ply"); }), 2,
       {"--out", "does not exist"}, {map}, {path("no_such_folder")}},
      {"--out in a read-only folder", mesh([&](auto& o) { o.out_path = str("readonly/m.ply"); }),
       2, {"--out", "is not writable"}, {map}, {path("readonly/m.ply")}, true},
      {"a missing map", mesh([&](auto& o) { o.map_path = str("nope.strata"); }), 2,
       {"nope.strata", "not found"}, {}, {ply}},
      {"a map that is a folder", mesh([&](auto& o) { o.map_path = str("a_folder"); }), 2,
       {"a_folder", "not a regular file"}, {}, {ply}},
      {"a file that is not a map", mesh([](auto&) {}), 2, {"is not a Strata map"}, {map}, {ply}},
  });
}

TEST_F(CliSweep, Esdf) {
  const fs::path map = path("map.strata"), png = path("slice.png");
  sweep({
      {"--slice-z nan", esdf([](auto& o) { o.slice_z_m = std::nanf(""); }), 2,
       {"--slice-z", "finite"}, {map}, {png}},
      {"--slice-z inf",
       esdf([](auto& o) { o.slice_z_m = -std::numeric_limits<float>::infinity(); }), 2,
       {"--slice-z", "finite"}, {map}, {png}},
      {"--max-distance 0", esdf([](auto& o) { o.max_distance_m = 0.0f; }), 2,
       {"--max-distance", "> 0"}, {map}, {png}},
      {"--max-distance nan", esdf([](auto& o) { o.max_distance_m = std::nanf(""); }), 2,
       {"--max-distance", "finite"}, {map}, {png}},
      {"--png over the map", esdf([&](auto& o) { o.png_path = map.string(); }), 2,
       {"--png", "same file as the input the map"}, {map}, {}},
      {"--png is a folder", esdf([&](auto& o) { o.png_path = str("a_folder"); }), 2,
       {"--png", "is a folder, not a file"}, {map, path("a_folder")}, {}},
      {"--png in a folder that does not exist",
       esdf([&](auto& o) { o.png_path = str("no_such_folder/s.png"); }), 2,
       {"--png", "does not exist"}, {map}, {path("no_such_folder")}},
      {"--png in a read-only folder", esdf([&](auto& o) { o.png_path = str("readonly/s.png"); }),
       2, {"--png", "is not writable"}, {map}, {path("readonly/s.png")}, true},
      {"a missing map", esdf([&](auto& o) { o.map_path = str("nope.strata"); }), 2,
       {"nope.strata", "not found"}, {}, {png}},
      {"a file that is not a map (before any device)", esdf([](auto&) {}), 2,
       {"is not a Strata map"}, {map}, {png}},
  });
}

/// A copy of the first frames of the shared EuRoC excerpt (calibration, IMU, truth) whose images
/// are blank: nothing to track. `right` adds cam1.
void writeBlankSession(const fs::path& source, const fs::path& session, bool right,
                       int frames) {
  const fs::path mav0 = session / "mav0";
  fs::create_directories(mav0 / "imu0");
  fs::copy_file(source / "mav0" / "imu0" / "sensor.yaml", mav0 / "imu0" / "sensor.yaml");
  fs::copy_file(source / "mav0" / "imu0" / "data.csv", mav0 / "imu0" / "data.csv");
  fs::copy_file(source / "groundtruth_body.txt", session / "groundtruth_body.txt");
  for (const char* cam : {"cam0", "cam1"}) {
    if (!right && std::string(cam) == "cam1") continue;
    fs::create_directories(mav0 / cam / "data");
    fs::copy_file(source / "mav0" / cam / "sensor.yaml", mav0 / cam / "sensor.yaml");
    std::ifstream csv(source / "mav0" / cam / "data.csv");
    std::ofstream out(mav0 / cam / "data.csv");
    std::string line;
    for (int row = 0; row <= frames && std::getline(csv, line); ++row) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      out << line << "\n";
      if (row == 0) continue;  // the header
      const std::string file = line.substr(line.find(',') + 1);
      writeGreyPng((mav0 / cam / "data" / file).string(), GreyImage(752, 480, 128));
    }
  }
}

TEST(CliSweepEuroc, NeverTrackingExitsThreeWithoutATrajectoryAndCam1IsNotOptional) {
  STRATA_REQUIRE_DATA("euroc_v101_micro/mav0", mav0);
  const fs::path source = fs::path(mav0).parent_path();
  const fs::path dir = test::freshTempDir("cli_sweep_euroc");
  writeBlankSession(source, dir / "stereo", true, 6);
  writeBlankSession(source, dir / "mono", false, 6);

  apps::OdometryOptions o;
  o.session_dir = (dir / "stereo").string();
  o.out_path = (dir / "stereo.txt").string();
  o.quiet = true;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runOdometry(o), 3);
  std::string err = testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  EXPECT_NE(err.find("no frame was tracked"), std::string::npos) << err;
  EXPECT_NE(err.find("no trajectory written"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "stereo.txt")) << "a run that tracked nothing writes no trajectory";
  EXPECT_TRUE(fs::exists(dir / "stereo.json")) << "its summary records the failure";

  o.session_dir = (dir / "mono").string();
  o.out_path = (dir / "mono.txt").string();
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runOdometry(o), 2) << "no cam1: refused, not run as mono";
  err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("--mono"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "mono.json"));

  o.mono = true;  // asked for: runs on cam0 (and tracks nothing on blank images)
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runOdometry(o), 3);
  err = testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  EXPECT_NE(err.find("no frame was tracked"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "mono.txt"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata
