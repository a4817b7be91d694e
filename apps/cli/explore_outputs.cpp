#include "cli/explore_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli/esdf_slice.h"
#include "cli/report_json.h"
#include "strata/core/atomic_file.h"
#include "strata/core/statistics.h"
#include "strata/explore/dead_end.h"

namespace strata::apps {
namespace {

Json optionalNumber(const std::optional<double>& value) {
  return value ? Json(*value) : Json(nullptr);
}

Json deadEndJson(const explore::ExplorationResult& r, const explore::DeadEnd& dead_end) {
  const explore::DeadEndEscape e =
      explore::analyseDeadEnd(r.flown_time_s, r.flown_W, dead_end, r.sim_time_s);
  Json j;
  j["entered"] = e.entered;
  j["entered_s"] = e.entered ? Json(e.entered_s) : Json(nullptr);
  j["deepest_s"] = e.entered ? Json(e.deepest_s) : Json(nullptr);
  j["deepest_m"] = jsonFloat(e.deepest_m);
  j["left_s"] = optionalNumber(e.left_s);
  j["escape_s"] = optionalNumber(e.escape_s);
  j["after_deepest_s"] = e.after_deepest_s;
  return j;
}

/// Each collision's closest approach: time, position and true clearance.
Json collisionEventsJson(const explore::ExplorationResult& r) {
  Json events = Json::array();
  for (const explore::CollisionEvent& e : r.collision_events) {
    Json j;
    j["time_s"] = e.time_s;
    j["p_W"] = jsonVector(e.p_W);
    j["clearance_m"] = jsonFloat(e.clearance_m);
    events.push_back(std::move(j));
  }
  return events;
}

/// `dead_end`: null without one.
Json runJson(const explore::ExplorationResult& r, Json dead_end) {
  const StepTimes times = stepTimes(r);
  const double t90 = timeToFraction(r, 0.9);
  std::size_t global_steps = 0;
  for (const auto& s : r.steps) global_steps += s.mode == "global" ? 1 : 0;
  Json j;
  j["explored_fraction"] = r.explored_fraction;
  j["time_to_90_s"] = t90 < 0.0 ? Json(nullptr) : Json(t90);
  j["collisions"] = r.collisions();
  j["collision_events"] = collisionEventsJson(r);
  j["min_clearance_m"] = jsonFloat(r.min_clearance_m);
  j["hit_obstacles"] = r.hit_obstacles;
  j["spheres_refused_by_hits"] = r.spheres_refused_by_hits;
  j["inflight_checks"] = r.inflight_checks;
  j["brakes"] = r.brakes;
  j["inflight_ms"] = r.inflight_ms;
  j["path_length_m"] = r.path_length_m;
  j["step_ms_median"] = times.median_ms;
  j["step_ms_p95"] = times.p95_ms;
  j["steps"] = r.steps.size();
  j["global_steps"] = global_steps;
  j["sim_time_s"] = r.sim_time_s;
  j["wall_s"] = r.wall_s;
  j["stop_reason"] = r.stop_reason;
  j["reachable_voxels"] = r.reachable_voxels;
  j["start_clearing_fraction"] = r.start_clearing_fraction;
  if (!dead_end.is_null()) j["dead_end"] = std::move(dead_end);
  return j;
}

}  // namespace

void writeExploreCurveCsv(const std::string& path, const explore::ExplorationResult& result) {
  std::ostringstream s;
  s << "sim_time_s,explored_fraction,path_length_m,compute_ms\n";
  char row[160];
  for (const explore::CurvePoint& p : result.curve) {
    std::snprintf(row, sizeof(row), "%.3f,%.6f,%.3f,%.3f\n", p.sim_time_s, p.explored_fraction,
                  p.path_length_m, p.compute_ms);
    s << row;
  }
  writeTextAtomically(path, s.str());
}

void writeExploreStepsCsv(const std::string& path, const explore::ExplorationResult& result) {
  std::ostringstream s;
  s << "sim_time_s,mode,best_gain_m3,tree_nodes,gain_evaluations,compute_ms,esdf_ms\n";
  char row[200];
  for (const explore::StepRecord& r : result.steps) {
    std::snprintf(row, sizeof(row), "%.3f,%s,%.4f,%zu,%zu,%.3f,%.3f\n", r.sim_time_s,
                  r.mode.c_str(), static_cast<double>(r.best_gain_m3), r.tree_nodes,
                  r.gain_evaluations, r.compute_ms, r.esdf_ms);
    s << row;
  }
  writeTextAtomically(path, s.str());
}

StepTimes stepTimes(const explore::ExplorationResult& result) {
  std::vector<double> ms;
  for (const explore::StepRecord& s : result.steps) ms.push_back(s.compute_ms);
  return {quantile(ms, 0.5), quantile(ms, 0.95)};
}

double timeToFraction(const explore::ExplorationResult& result, double fraction) {
  for (const explore::CurvePoint& p : result.curve) {
    if (p.explored_fraction >= fraction) return p.sim_time_s;
  }
  return -1.0;
}

void writeExploreReport(const std::string& path, const std::string& world,
                        const std::vector<explore::ExplorationResult>& results,
                        const explore::ExplorationConfig& config, const Eigen::Vector3f& start_W,
                        unsigned long long seed, const std::optional<explore::DeadEnd>& dead_end) {
  Json planners = Json::object();
  for (const explore::ExplorationResult& r : results) {
    planners[r.planner] = runJson(r, dead_end ? deadEndJson(r, *dead_end) : Json(nullptr));
  }
  Json j;
  j["world"] = world;
  j["seed"] = seed;
  j["start"] = jsonVector(start_W);
  j["voxel_size_m"] = jsonFloat(config.voxel_size_m);
  j["time_limit_s"] = config.time_limit_s;
  j["camera"] = Json::array({config.camera_width_px, config.camera_height_px});
  j["planners"] = std::move(planners);
  writeTextAtomically(path, jsonFileText(j));
}

}  // namespace strata::apps
