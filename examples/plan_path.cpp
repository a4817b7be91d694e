// Loads a saved map (Mapper::save, `strata fuse`), computes its ESDF and plans a path for a
// spherical robot between two points with one of strata::plan's planners; prints the path.
//   plan_path MAP.strata X0,Y0,Z0 X1,Y1,Z1 [grid|topo|rrt] [RADIUS_M]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include "strata/mapper/mapper.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/planner_factory.h"
#include "strata/vk/vk.h"

namespace {

Eigen::Vector3f parsePoint(const char* text) {
  Eigen::Vector3f p;
  char end = 0;
  if (std::sscanf(text, "%f,%f,%f%c", &p.x(), &p.y(), &p.z(), &end) != 3)
    throw std::invalid_argument(std::string("expected a point x,y,z in metres, got '") + text +
                                "'");
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: plan_path MAP.strata X0,Y0,Z0 X1,Y1,Z1 [grid|topo|rrt] [RADIUS_M]\n");
    return 2;
  }
  try {
    strata::plan::PlanRequest request;
    request.start_W = parsePoint(argv[2]);
    request.goal_W = parsePoint(argv[3]);
    const std::string planner_name = argc > 4 ? argv[4] : "grid";
    if (argc > 5) request.radius_m = std::strtof(argv[5], nullptr);
    const auto context = strata::vk::Context::create();
    strata::MapperConfig config;
    config.esdf = true;  // esdf_config.max_distance_m (2 m) must exceed the robot's radius
    const auto mapper = strata::Mapper::load(argv[1], *context, config);
    mapper->updateEsdf();
    const strata::EsdfMap& esdf = mapper->esdf();  // the host copy the planners search
    strata::plan::HostCollisionChecker checker(esdf);
    for (const auto& [what, p] :
         {std::pair{"start", request.start_W}, std::pair{"goal", request.goal_W}}) {
      const std::string problem =
          strata::plan::endpointProblem(esdf, checker, what, p, request.radius_m, request.unknown);
      if (!problem.empty()) throw std::invalid_argument(problem);
    }
    const auto planner =
        strata::plan::makePlanner(planner_name, esdf, checker, {request.radius_m, request.unknown});
    const strata::plan::PlanResult result = planner->plan(request);
    if (!result.success) {
      std::printf("no path (%s): %s\n", planner->name().c_str(), result.message.c_str());
      return 1;
    }
    for (const Eigen::Vector3f& p : result.path_W)
      std::printf("  %.2f %.2f %.2f\n", p.x(), p.y(), p.z());
    std::printf("%s: %.2f m through %zu waypoints, clearance %.2f m, %.2f ms\n",
                planner->name().c_str(), result.length_m, result.path_W.size(),
                result.min_clearance_m, result.planning_ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plan_path: %s\n", e.what());
    return 1;
  }
  return 0;
}
