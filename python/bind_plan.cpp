// strata.plan (bindings.h): the library's planners (plan/planner_factory.h: grid A*, the
// topological map, RRT*) on a Mapper's ESDF, as `strata plan` runs them on a saved map.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "py_mapper.h"
#include "strata/core/error.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/planner_factory.h"

namespace strata::python {
namespace {

/// A PlanResult with the path as an N x 3 float64 array and the planner's build time.
struct PyPlanResult {
  plan::PlanResult result;
  double build_ms = 0.0;
};

UnknownPolicy unknownPolicyFrom(const std::string& text) {
  if (text == "occupied") return UnknownPolicy::kOccupied;
  if (text == "free") return UnknownPolicy::kFree;
  throw InputError("unknown must be 'occupied' or 'free', not '" + text + "'");
}

/// 3 numbers (a list, tuple or array) as a point; InputError otherwise.
Eigen::Vector3f pointFrom(const py::object& p, const char* what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(p);
  if (!a || a.size() != 3) {
    PyErr_Clear();
    throw InputError(std::string(what) + " must be 3 numbers (x, y, z), not " +
                     std::string(py::repr(p)));
  }
  const Eigen::Vector3f out(static_cast<float>(a.data()[0]), static_cast<float>(a.data()[1]),
                            static_cast<float>(a.data()[2]));
  if (!out.allFinite()) throw InputError(std::string(what) + " is not finite");
  return out;
}

/// As `strata plan`: the endpoints checked first (InputError naming the bad one), then the
/// planner built for the robot and asked once. The Mapper's host ESDF copy is read.
PyPlanResult planOn(PyMapper& self, const py::object& start, const py::object& goal,
                    const std::string& planner, float radius_m, const std::string& unknown,
                    double time_budget_s, std::uint64_t seed) {
  plan::PlanRequest request;
  request.start_W = pointFrom(start, "start");
  request.goal_W = pointFrom(goal, "goal");
  request.radius_m = radius_m;
  request.unknown = unknownPolicyFrom(unknown);
  if (!(time_budget_s > 0.0)) throw InputError("time_budget_s must be > 0");
  request.time_budget_s = time_budget_s;
  request.seed = seed;
  return withoutGil(self, [&](Mapper& mapper) {
    const EsdfMap& esdf = mapper.esdf();
    plan::HostCollisionChecker checker(esdf);
    for (const auto& [what, p] :
         {std::pair{"start", request.start_W}, std::pair{"goal", request.goal_W}}) {
      const std::string problem =
          plan::endpointProblem(esdf, checker, what, p, request.radius_m, request.unknown);
      if (!problem.empty()) throw InputError(problem);
    }
    const std::unique_ptr<plan::Planner> p = plan::makePlanner(
        planner, esdf, checker, plan::PlannerOptions{request.radius_m, request.unknown});
    PyPlanResult out;
    out.build_ms = plan::plannerBuildMs(*p);
    out.result = p->plan(request);
    return out;
  });
}

py::array_t<double> pathArray(const std::vector<Eigen::Vector3f>& path) {
  py::array_t<double> out({static_cast<py::ssize_t>(path.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < path.size(); ++i)
    for (int k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), k) = path[i][k];
  return out;
}

}  // namespace

void bindPlan(py::module_& p) {
  py::class_<PyPlanResult>(p, "PlanResult", "What plan() found (plan/plan_types.h PlanResult).")
      .def_property_readonly(
          "success", [](const PyPlanResult& r) { return r.result.success; },
          "Whether a path was found")
      .def_property_readonly(
          "message", [](const PyPlanResult& r) { return r.result.message; },
          "Why there is no path, or ''")
      .def_property_readonly(
          "path", [](const PyPlanResult& r) { return pathArray(r.result.path_W); },
          "N x 3 float64, start ... goal (world frame, metres); 0 x 3 without success")
      .def_property_readonly(
          "length_m", [](const PyPlanResult& r) { return r.result.length_m; },
          "Sum of the path's segment lengths")
      .def_property_readonly(
          "min_clearance_m", [](const PyPlanResult& r) { return r.result.min_clearance_m; },
          "Smallest ESDF distance along the path (every half voxel)")
      .def_property_readonly(
          "planning_ms", [](const PyPlanResult& r) { return r.result.planning_ms; },
          "Wall-clock time of the query")
      .def_property_readonly(
          "build_ms", [](const PyPlanResult& r) { return r.build_ms; },
          "Wall-clock time of building the planner's structures (grid, graph)")
      .def_property_readonly(
          "collision_checks", [](const PyPlanResult& r) { return r.result.collision_checks; },
          "Sphere tests the query ran")
      .def("__repr__", [](const PyPlanResult& r) {
        return r.result.success ? "PlanResult(" + std::to_string(r.result.path_W.size()) +
                                      " waypoints, " + std::to_string(r.result.length_m) + " m)"
                                : "PlanResult(no path: " + r.result.message + ")";
      });
  p.def("plan", &planOn, py::arg("mapper"), py::arg("start"), py::arg("goal"),
        py::arg("planner") = "grid", py::arg("radius_m") = 0.3f, py::arg("unknown") = "occupied",
        py::arg("time_budget_s") = 1.0, py::arg("seed") = 1,
        "A collision-free path for a sphere of radius_m from start to goal (3 numbers each, world "
        "frame) through the mapper's ESDF (after update_esdf; MapConfig(allocate_free_space=True) "
        "so free space is mapped), as `strata plan`: planner 'grid' (A*), 'topo' (topological "
        "map) or 'rrt' (RRT*, time_budget_s and seed); unknown space 'occupied' or 'free'. A start "
        "or goal in collision or outside the map raises InputError; an unreachable goal gives a "
        "PlanResult with success False and its message. The GIL is released while it plans.");
}

}  // namespace strata::python
