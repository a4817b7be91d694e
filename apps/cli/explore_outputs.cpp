#include "cli/explore_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli/esdf_slice.h"
#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/statistics.h"
#include "explore/dead_end.h"

namespace strata::apps {
namespace {

std::string optionalNumber(const std::optional<double>& value) {
  return value ? jsonNumber(*value) : std::string("null");
}

std::string deadEndJson(const explore::ExplorationResult& r, const explore::DeadEnd& dead_end) {
  const explore::DeadEndEscape e =
      explore::analyseDeadEnd(r.flown_time_s, r.flown_W, dead_end, r.sim_time_s);
  std::ostringstream j;
  j << "{\"entered\": " << (e.entered ? "true" : "false")
    << ", \"entered_s\": " << (e.entered ? jsonNumber(e.entered_s) : "null")
    << ", \"deepest_s\": " << (e.entered ? jsonNumber(e.deepest_s) : "null")
    << ", \"deepest_m\": " << jsonNumber(e.deepest_m)
    << ", \"left_s\": " << optionalNumber(e.left_s)
    << ", \"escape_s\": " << optionalNumber(e.escape_s)
    << ", \"after_deepest_s\": " << jsonNumber(e.after_deepest_s) << "}";
  return j.str();
}

/// Each collision's closest approach: time, position and true clearance.
std::string collisionEventsJson(const explore::ExplorationResult& r) {
  std::ostringstream j;
  for (std::size_t i = 0; i < r.collision_events.size(); ++i) {
    const explore::CollisionEvent& e = r.collision_events[i];
    j << (i ? ", " : "") << "{\"time_s\": " << jsonNumber(e.time_s) << ", \"p_W\": ["
      << jsonNumber(e.p_W.x()) << ", " << jsonNumber(e.p_W.y()) << ", " << jsonNumber(e.p_W.z())
      << "], \"clearance_m\": " << jsonNumber(e.clearance_m) << "}";
  }
  return j.str();
}

std::string runJson(const explore::ExplorationResult& r, const std::string& dead_end_json) {
  const StepTimes times = stepTimes(r);
  const double t90 = timeToFraction(r, 0.9);
  std::size_t global_steps = 0;
  for (const auto& s : r.steps) global_steps += s.mode == "global" ? 1 : 0;
  std::ostringstream j;
  j << "{\"explored_fraction\": " << jsonNumber(r.explored_fraction)
    << ", \"time_to_90_s\": " << (t90 < 0.0 ? "null" : jsonNumber(t90))
    << ", \"collisions\": " << r.collisions() << ", \"collision_events\": ["
    << collisionEventsJson(r) << "]"
    << ", \"min_clearance_m\": " << jsonNumber(r.min_clearance_m)
    << ", \"hit_obstacles\": " << r.hit_obstacles
    << ", \"spheres_refused_by_hits\": " << r.spheres_refused_by_hits
    << ", \"inflight_checks\": " << r.inflight_checks << ", \"brakes\": " << r.brakes
    << ", \"inflight_ms\": " << jsonNumber(r.inflight_ms)
    << ", \"path_length_m\": " << jsonNumber(r.path_length_m)
    << ", \"step_ms_median\": " << jsonNumber(times.median_ms)
    << ", \"step_ms_p95\": " << jsonNumber(times.p95_ms) << ", \"steps\": " << r.steps.size()
    << ", \"global_steps\": " << global_steps << ", \"sim_time_s\": " << jsonNumber(r.sim_time_s)
    << ", \"wall_s\": " << jsonNumber(r.wall_s)
    << ", \"stop_reason\": " << jsonQuoted(r.stop_reason)
    << ", \"reachable_voxels\": " << r.reachable_voxels
    << ", \"start_clearing_fraction\": " << jsonNumber(r.start_clearing_fraction);
  if (!dead_end_json.empty()) j << ", \"dead_end\": " << dead_end_json;
  j << "}";
  return j.str();
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
  std::ostringstream j;
  j << "{\n  \"world\": " << jsonQuoted(world) << ",\n  \"seed\": " << seed << ",\n  \"start\": ["
    << jsonNumber(start_W.x()) << ", " << jsonNumber(start_W.y()) << ", " << jsonNumber(start_W.z())
    << "],\n  \"voxel_size_m\": " << jsonNumber(config.voxel_size_m)
    << ",\n  \"time_limit_s\": " << jsonNumber(config.time_limit_s) << ",\n  \"camera\": ["
    << config.camera_width_px << ", " << config.camera_height_px << "],\n  \"planners\": {";
  for (std::size_t i = 0; i < results.size(); ++i) {
    j << (i ? ",\n    " : "\n    ") << jsonQuoted(results[i].planner) << ": "
      << runJson(results[i], dead_end ? deadEndJson(results[i], *dead_end) : "");
  }
  j << "\n  }\n}\n";
  writeTextAtomically(path, j.str());
}

}  // namespace strata::apps
