// The package's data side (bindings.h): datasets and simulated sessions as arrays, VIO over
// EuRoC folders, trajectory evaluation.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "py_dataset.h"
#include "strata/core/error.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/open_dataset.h"
#include "strata/odometry/pipeline/vio_pipeline.h"
#include "strata/odometry/pipeline/vio_replay.h"
#include "strata/sim/session/drifted_session.h"
#include "strata/sim/sim_setup.h"
#include "strata/sim/world/world_paths.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::python {
namespace {

/// A VIO run over an EuRoC folder: the left camera's trajectory and the pipeline's counts.
struct VioRun {
  bool stereo = true;
  py::array_t<double> trajectory;  // N x 8, tracked frames
  py::array_t<double> truth;       // M x 8, the left camera's truth (0 x 8 without)
  std::size_t frames_processed = 0;
  std::size_t frames_tracked = 0;
  std::vector<std::pair<double, std::string>> failures;  // (t_s, reason)
  std::size_t imu_out_of_range = 0;
  double wall_s = 0.0;
};

VioRun runEuroc(const std::string& folder, bool mono, std::size_t frames, int window) {
  euroc::ReaderOptions reader;
  reader.use_right_camera = !mono;
  const euroc::EurocDataset dataset = euroc::EurocDataset::open(folder, reader);
  if (!mono && !dataset.stereo()) {
    throw InputError(folder +
                     ": the session has no right camera: stereo VIO needs it; pass "
                     "mono=True to run on cam0 alone");
  }
  odometry::VioPipelineConfig config;
  config.mono = mono;
  config.backend.window_size = window;
  config.validate();
  odometry::ReplayInput input;
  input.imu = &dataset.imu();
  for (const auto& f : dataset.frames()) input.frame_timestamps_ns.push_back(f.timestamp_ns);
  // Ctrl-C: the replay asks for each frame's images here, so a pending signal (KeyboardInterrupt)
  // stops it between frames, with the GIL taken just for the check.
  input.load = [&](std::size_t k) {
    {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    return dataset.loadImages(k);
  };
  input.max_frames = frames;
  odometry::ReplayResult result;
  {
    py::gil_scoped_release release;
    odometry::VioPipeline pipeline(dataset.calibration(), config);
    result = odometry::replayVio(pipeline, input);
  }
  VioRun run;
  run.stereo = result.stereo;
  std::vector<std::pair<double, Eigen::Isometry3d>> poses, truth;
  for (const auto& f : result.tracked) poses.emplace_back(1e-9 * f.timestamp_ns, f.T_W_C);
  const Eigen::Isometry3d& T_B_C = dataset.calibration().cameras.at(0).T_B_C;
  for (const auto& g : dataset.groundTruth())
    truth.emplace_back(1e-9 * g.timestamp_ns, g.T_W_B * T_B_C);
  run.trajectory = tumArray(poses);
  run.truth = tumArray(truth);
  run.frames_processed = result.stats.frames_processed;
  run.frames_tracked = result.stats.frames_tracking;
  for (const auto& [t_ns, reason] : result.stats.failure_log)
    run.failures.emplace_back(1e-9 * t_ns, reason);
  run.imu_out_of_range = result.stats.imu_out_of_range_skipped;
  run.wall_s = result.wall_s;
  return run;
}

}  // namespace

void bindIo(py::module_& io) {
  py::class_<PyDataset>(io, "Dataset",
                        "A TUM RGB-D or 7-Scenes folder: len(), [i] -> dict(depth float32 "
                        "metres H x W, color uint8 H x W x 3 or None, T_W_C 4 x 4, timestamp_s, "
                        "name), intrinsics.")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("__len__", &PyDataset::size)
      .def("__getitem__", &PyDataset::frame, py::arg("index"))
      .def_property_readonly("intrinsics", &PyDataset::intrinsics)
      .def_property_readonly("name", &PyDataset::name)
      .def_property_readonly("recorded_frames", &PyDataset::recordedFrames,
                             "Frames of the whole recording (a simulated path at its rate)")
      .def("__repr__", [](const PyDataset& d) {
        return "Dataset(" + d.name() + ", " + std::to_string(d.size()) + " frames)";
      });
}

void bindTrajectory(py::module_& t) {
  py::class_<trajectory::TrajectoryError>(t, "TrajectoryError",
                                          "ATE and RPE of an estimate against the truth.")
      .def_readonly("matched", &trajectory::TrajectoryError::matched)
      .def_readonly("ate_rmse_m", &trajectory::TrajectoryError::ate_rmse_m)
      .def_readonly("ate_max_m", &trajectory::TrajectoryError::ate_max_m)
      .def_readonly("path_length_m", &trajectory::TrajectoryError::path_length_m)
      .def_readonly("rpe_trans_percent", &trajectory::TrajectoryError::rpe_trans_percent)
      .def_readonly("rpe_rot_deg_per_m", &trajectory::TrajectoryError::rpe_rot_deg_per_m)
      .def_readonly("scale", &trajectory::TrajectoryError::scale)
      .def_property_readonly(
          "aligned_positions",
          [](const trajectory::TrajectoryError& e) { return rows(e.estimate_positions_m); },
          "N x 3: the matched estimate positions after the alignment")
      .def_property_readonly(
          "truth_positions",
          [](const trajectory::TrajectoryError& e) { return rows(e.truth_positions_m); },
          "N x 3: the truth positions they were matched to")
      .def("__repr__", [](const trajectory::TrajectoryError& e) {
        std::ostringstream s;
        s << "TrajectoryError(matched=" << e.matched << ", ate_rmse_m=" << e.ate_rmse_m
          << ", ate_max_m=" << e.ate_max_m << ", path_length_m=" << e.path_length_m << ")";
        return s.str();
      });
  t.def(
      "evaluate",
      [](const py::array& estimate, const py::array& truth, const std::string& alignment) {
        trajectory::Alignment a;
        if (alignment == "se3") {
          a = trajectory::Alignment::kSE3;
        } else if (alignment == "sim3") {
          a = trajectory::Alignment::kSim3;
        } else {
          throw InputError("alignment must be 'se3' or 'sim3', not '" + alignment + "'");
        }
        return trajectory::evaluateTrajectory(timedPosesFrom(estimate, "estimate"),
                                              timedPosesFrom(truth, "truth"), a);
      },
      py::arg("estimate"), py::arg("truth"), py::arg("alignment") = "se3",
      "ATE/RPE of N x 8 TUM-order arrays (t, x, y, z, qx, qy, qz, qw), matched by time.");
}

void bindSim(py::module_& s) {
  s.def(
      "session",
      [](const std::string& world, int session, int frames, double rate_hz, bool noise) {
        const auto loaded = sim::loadWorld(sim::findWorld(world), 0, 0);
        if (frames < 0) throw InputError("frames must be >= 0 (0: every frame of the path)");
        auto dataset = std::make_unique<sim::SimSessionDataset>(
            loaded, session, sim::sessionConfig(rate_hz, frames, noise, false));
        return std::make_unique<PyDataset>(std::move(dataset));
      },
      py::arg("world") = "room", py::arg("session") = 0, py::arg("frames") = 30,
      py::arg("rate_hz") = 30.0, py::arg("noise") = true,
      "A simulated session of a world (a shipped name: room, office, warehouse, deadend, or a "
      "world file) as a Dataset: `frames` frames spread over the session's path (0: all at "
      "rate_hz), rendered when indexed, with the simulator's depth noise unless noise=False.");
  s.def(
      "drifted_session",
      [](const std::string& source, const std::string& out, std::size_t first_frame,
         std::optional<std::size_t> last_frame, std::uint64_t seed, bool drift, bool offset) {
        sim::DriftedSessionConfig config;
        config.first_frame = first_frame;
        config.last_frame = last_frame;
        config.seed = seed;
        config.offset = offset;
        if (!drift) {
          config.drift.translation_sigma_m_per_sqrt_m = 0.0;
          config.drift.yaw_sigma_rad_per_sqrt_m = 0.0;
        }
        config.validate();
        sim::DriftedSession session;
        {
          py::gil_scoped_release release;
          session = sim::writeDriftedSession(source, out, config);
        }
        py::dict result;
        result["T_W_S"] = poseTo(session.T_W_S);
        result["frames"] = session.frames;
        result["frames_dropped"] = session.frames_dropped;
        return result;
      },
      py::arg("source"), py::arg("out"), py::arg("first_frame") = 0,
      py::arg("last_frame") = py::none(), py::arg("seed") = 1, py::arg("drift") = true,
      py::arg("offset") = true,
      "Writes `out` as a session folder (TUM layout) from frames first_frame..last_frame "
      "(inclusive; None: to the end) of the TUM folder `source`, for alignment: odometry.txt is "
      "the truth with odometry drift (drift=False: none) in a random frame of its own "
      "(offset=False: the source's), groundtruth.txt the truth; images are listed, not copied. "
      "Returns dict(T_W_S 4 x 4: the true session-to-world, frames, frames_dropped).");
}

void bindOdometry(py::module_& o) {
  py::class_<VioRun>(o, "VioRun", "What run_euroc gives: the left camera's trajectory and counts.")
      .def_readonly("stereo", &VioRun::stereo)
      .def_readonly("trajectory", &VioRun::trajectory,
                    "N x 8 (t, x, y, z, qx, qy, qz, qw): the tracked frames' left camera to world")
      .def_readonly("truth", &VioRun::truth, "M x 8: the left camera's truth (0 x 8 without)")
      .def_readonly("frames_processed", &VioRun::frames_processed)
      .def_readonly("frames_tracked", &VioRun::frames_tracked)
      .def_readonly("failures", &VioRun::failures, "[(t_s, reason)]")
      .def_readonly("imu_out_of_range", &VioRun::imu_out_of_range)
      .def_readonly("wall_s", &VioRun::wall_s)
      .def("__repr__", [](const VioRun& r) {
        return "VioRun(" + std::string(r.stereo ? "stereo" : "mono") + ", " +
               std::to_string(r.frames_tracked) + " of " + std::to_string(r.frames_processed) +
               " frames tracked, " + std::to_string(r.failures.size()) + " failures)";
      });
  o.def("run_euroc", &runEuroc, py::arg("folder"), py::arg("mono") = false, py::arg("frames") = 0,
        py::arg("window") = 10,
        "Visual-inertial odometry over an EuRoC/ASL folder (mav0/), as `strata odometry`: "
        "frames > 0 processes only the first frames. The GIL is released while it runs; Ctrl-C "
        "(a pending signal) stops it between frames.");
}

}  // namespace strata::python
