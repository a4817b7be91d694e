#pragma once
// The files of `strata plan`: the path as CSV, the report as JSON, the picture.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "strata/map/esdf_layer.h"
#include "strata/plan/plan_types.h"

namespace strata::apps {

struct PlanReport {
  std::string planner;
  plan::PlanRequest request;
  plan::PlanResult result;
  double build_ms = 0.0;
  std::size_t memory_bytes = 0;
};

/// "x,y,z" header, one waypoint a line (metres, world frame). Written atomically.
void writePathCsv(const std::string& path, const std::vector<Eigen::Vector3f>& path_W);
/// planner, success, message, length_m, min_clearance_m, planning_ms, build_ms,
/// collision_checks, memory_bytes, start, goal, radius_m, unknown, waypoints. Atomically.
void writePlanReport(const std::string& path, const PlanReport& report);
/// The ESDF slice at the path's mean height (the start's and goal's without a path), the path as
/// a polyline, the start as a green and the goal as a red disc. InputError when no block holds
/// that height.
void writePathPng(const std::string& path, const EsdfMap& esdf, const PlanReport& report);

}  // namespace strata::apps
