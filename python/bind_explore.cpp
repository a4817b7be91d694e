// strata.explore (bindings.h): closed-loop exploration of a simulated world, as `strata explore`
// runs it (explore/exploration_loop.h): a MAV with an RGB-D camera flies what the planner asks,
// its frames fused by a Mapper, until the time limit, the target share or no gain. The GIL is
// released while it runs; Ctrl-C stops it at the next evaluation of the explored share.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "py_mapper.h"
#include "strata/core/error.h"
#include "strata/explore/exploration_loop.h"
#include "strata/explore/history_planner.h"
#include "strata/explore/nbvp_planner.h"
#include "strata/sim/sim_setup.h"
#include "strata/sim/world/world_paths.h"

namespace strata::python {
namespace {

constexpr float kStartHeightM = 1.2f;  // as `strata explore`

/// An exploration run as arrays.
struct PyExplorationRun {
  std::string planner;
  py::array_t<double> curve;  // N x 4: sim_time_s, explored_fraction, path_length_m, compute_ms
  py::array_t<double> flown;  // M x 3, world frame
  py::array_t<double> flown_time_s;  // M
  py::array_t<double> start;         // 3
  double explored_fraction = 0.0, path_length_m = 0.0, sim_time_s = 0.0, wall_s = 0.0;
  double start_clearing_fraction = 0.0;
  float min_clearance_m = 0.0f;
  int collisions = 0;
  std::size_t reachable_voxels = 0, planning_steps = 0;
  std::string stop_reason;
  PyMesh mesh;  // the map's, at the end
};

std::unique_ptr<explore::ExplorationPlanner> plannerFor(const std::string& name,
                                                        std::uint64_t seed) {
  if (name == "history") {
    explore::HistoryConfig c;
    c.seed = seed;
    return std::make_unique<explore::HistoryPlanner>(c);
  }
  if (name == "nbvp") {
    explore::NbvpConfig c;
    c.seed = seed;
    return std::make_unique<explore::NbvpPlanner>(c);
  }
  throw InputError("planner must be 'history' or 'nbvp', not '" + name + "'");
}

PyExplorationRun runFrom(const explore::ExplorationResult& r, const Eigen::Vector3f& start,
                         const Mesh& mesh) {
  PyExplorationRun out;
  out.planner = r.planner;
  out.curve = py::array_t<double>({static_cast<py::ssize_t>(r.curve.size()), py::ssize_t{4}});
  for (std::size_t i = 0; i < r.curve.size(); ++i) {
    const explore::CurvePoint& p = r.curve[i];
    const double row[4] = {p.sim_time_s, p.explored_fraction, p.path_length_m, p.compute_ms};
    for (int k = 0; k < 4; ++k) out.curve.mutable_at(i, k) = row[k];
  }
  std::vector<Eigen::Vector3d> flown;
  for (const Eigen::Vector3f& p : r.flown_W) flown.push_back(p.cast<double>());
  out.flown = rows(flown);
  out.flown_time_s = py::array_t<double>(static_cast<py::ssize_t>(r.flown_time_s.size()));
  std::copy(r.flown_time_s.begin(), r.flown_time_s.end(), out.flown_time_s.mutable_data());
  out.start = py::array_t<double>(3);
  for (int k = 0; k < 3; ++k) out.start.mutable_at(k) = start[k];
  out.explored_fraction = r.explored_fraction;
  out.path_length_m = r.path_length_m;
  out.sim_time_s = r.sim_time_s;
  out.wall_s = r.wall_s;
  out.start_clearing_fraction = r.start_clearing_fraction;
  out.min_clearance_m = r.min_clearance_m;
  out.collisions = r.collisions();
  out.reachable_voxels = r.reachable_voxels;
  out.planning_steps = r.steps.size();
  out.stop_reason = r.stop_reason;
  out.mesh = meshTo(mesh);
  return out;
}

PyExplorationRun runExploration(const std::string& world_name, const std::string& planner_name,
                                double time_limit_s, const py::object& voxel_size, const py::object& start,
                                double start_yaw_deg, int width, int height, double eval_period_s,
                                std::uint64_t seed, const py::object& device) {
  auto planner = plannerFor(planner_name, seed);
  const auto world = sim::loadWorld(sim::findWorld(world_name), 0, 1);
  // None: the world's default voxel, as strata explore (explore::defaultVoxelSize).
  if (!voxel_size.is_none() && !py::isinstance<py::float_>(voxel_size) &&
      !py::isinstance<py::int_>(voxel_size)) {
    throw InputError("voxel_size_m must be a number or None, not " +
                     std::string(py::repr(voxel_size)));
  }
  const float voxel_size_m = voxel_size.is_none() ? explore::defaultVoxelSize(*world)
                                                  : voxel_size.cast<float>();
  explore::ExplorationConfig config;
  config.time_limit_s = time_limit_s;
  config.voxel_size_m = voxel_size_m;
  config.camera_width_px = width;
  config.camera_height_px = height;
  config.eval_period_s = eval_period_s;
  config.seed = seed;
  config.validate();
  if (!std::isfinite(start_yaw_deg)) throw InputError("start_yaw_deg must be finite");
  Eigen::Vector3f start_W;
  if (start.is_none()) {
    start_W = explore::defaultStart(*world, kStartHeightM, config);
  } else {
    const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(start);
    if (!p || p.size() != 3) {
      PyErr_Clear();
      throw InputError("start must be 3 numbers (x, y, z), not " + std::string(py::repr(start)));
    }
    start_W = Eigen::Vector3f(static_cast<float>(p.data()[0]), static_cast<float>(p.data()[1]),
                              static_cast<float>(p.data()[2]));
    if (!start_W.allFinite()) throw InputError("start is not finite");
  }
  const auto context =
      PyMapper::makeContext(device.is_none() ? "" : py::str(device).cast<std::string>());
  py::gil_scoped_release release;
  const Eigen::AlignedBox3d b = world->bounds();
  const explore::ExplorationTruth truth(*world, {b.min().cast<float>(), b.max().cast<float>()},
                                        start_W, voxel_size_m);
  explore::ExplorationLoop loop(
      *world, truth, config, {start_W, static_cast<float>(start_yaw_deg * M_PI / 180.0)}, *context);
  // Ctrl-C: a pending signal (KeyboardInterrupt) stops the run at the next curve point.
  const explore::ExplorationResult result =
      loop.run(*planner, [](const explore::CurvePoint&, const explore::StepRecord*) {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      });
  const Mesh mesh = loop.mapper().mesh();
  py::gil_scoped_acquire gil;
  return runFrom(result, start_W, mesh);
}

}  // namespace

void bindExplore(py::module_& e) {
  py::class_<PyExplorationRun>(e, "ExplorationRun", "What run() did (ExplorationResult).")
      .def_readonly("planner", &PyExplorationRun::planner)
      .def_readonly("curve", &PyExplorationRun::curve,
                    "N x 4 float64 over time: sim_time_s, explored_fraction (of the reachable "
                    "free volume), path_length_m, compute_ms (mean planning step since the last "
                    "row)")
      .def_readonly("flown", &PyExplorationRun::flown,
                    "M x 3 float64: the positions flown (world frame), one motion step apart")
      .def_readonly("flown_time_s", &PyExplorationRun::flown_time_s, "M: their simulated times")
      .def_readonly("start", &PyExplorationRun::start, "3: where it started")
      .def_readonly("explored_fraction", &PyExplorationRun::explored_fraction, "At the end")
      .def_readonly("path_length_m", &PyExplorationRun::path_length_m)
      .def_readonly("sim_time_s", &PyExplorationRun::sim_time_s)
      .def_readonly("wall_s", &PyExplorationRun::wall_s)
      .def_readonly("start_clearing_fraction", &PyExplorationRun::start_clearing_fraction,
                    "Share of the reachable volume entered by clearing the start, not seen")
      .def_readonly("min_clearance_m", &PyExplorationRun::min_clearance_m,
                    "Smallest true distance from the flown path to a surface")
      .def_readonly("collisions", &PyExplorationRun::collisions,
                    "Stretches of the path closer to a surface than the robot's radius")
      .def_readonly("reachable_voxels", &PyExplorationRun::reachable_voxels)
      .def_readonly("planning_steps", &PyExplorationRun::planning_steps)
      .def_readonly("stop_reason", &PyExplorationRun::stop_reason,
                    "'target', 'time limit', 'no gain' or 'stuck'")
      .def_readonly("mesh", &PyExplorationRun::mesh, "The explored map's mesh at the end")
      .def("__repr__", [](const PyExplorationRun& r) {
        return "ExplorationRun(" + r.planner + ", explored " +
               std::to_string(100.0 * r.explored_fraction) + " % in " +
               std::to_string(r.sim_time_s) + " s, " + r.stop_reason + ")";
      });
  e.def("run", &runExploration, py::arg("world") = "room", py::arg("planner") = "history",
        py::arg("time_limit_s") = 60.0, py::arg("voxel_size_m") = py::none(),
        py::arg("start") = py::none(), py::arg("start_yaw_deg") = 0.0, py::arg("width") = 160,
        py::arg("height") = 120, py::arg("eval_period_s") = 5.0, py::arg("seed") = 1,
        py::arg("device") = py::none(),
        "Explores a simulated world (a shipped name or a world file) with a MAV, as `strata "
        "explore`: planner 'history' or 'nbvp', for time_limit_s simulated seconds (or until "
        "the target share, no gain, stuck), from `start` (3 numbers; None: the first room's "
        "centre at 1.2 m) facing start_yaw_deg; voxel_size_m None: the world's default (5 cm where "
        "the world is small enough, else 10 cm, as strata explore). The GIL is released while it runs; Ctrl-C "
        "stops it at the next evaluation (every eval_period_s simulated).");
}

}  // namespace strata::python
