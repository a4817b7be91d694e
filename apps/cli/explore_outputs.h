#pragma once
// The files of `strata explore`: the curve as CSV, the report as JSON, the explored-share chart
// and the top-down picture of the flown path over the final map's ESDF.
#include <optional>
#include <string>
#include <vector>

#include "strata/explore/dead_end.h"
#include "strata/explore/exploration_loop.h"

namespace strata::apps {

/// sim_time_s, explored_fraction, path_length_m, compute_ms (one row per curve point).
void writeExploreCurveCsv(const std::string& path, const explore::ExplorationResult& result);

/// One row per planning step: sim_time_s, mode, best_gain_m3, tree_nodes, gain_evaluations,
/// compute_ms, esdf_ms.
void writeExploreStepsCsv(const std::string& path, const explore::ExplorationResult& result);

/// Median and 95th percentile of the planning steps' compute times (ms); 0 without steps.
struct StepTimes {
  double median_ms = 0.0;
  double p95_ms = 0.0;
};
StepTimes stepTimes(const explore::ExplorationResult& result);
/// The first curve time at which the explored share reaches `fraction`; negative: never.
double timeToFraction(const explore::ExplorationResult& result, double fraction);

/// {"world":..., "planners": {"history": {...}, ...}}; with `dead_end` (explore/dead_end.h) each
/// planner also gets "dead_end": entered_s, deepest_s, deepest_m, left_s, escape_s (null: never
/// left), after_deepest_s.
void writeExploreReport(const std::string& path, const std::string& world,
                        const std::vector<explore::ExplorationResult>& results,
                        const explore::ExplorationConfig& config, const Eigen::Vector3f& start_W,
                        unsigned long long seed,
                        const std::optional<explore::DeadEnd>& dead_end = std::nullopt);

/// Explored share vs simulated time, one line per run.
void writeExploreCurvePng(const std::string& path, const std::string& world,
                          const std::vector<explore::ExplorationResult>& results);

/// The ESDF slice at the start's height with the flown path drawn over it.
void writeExplorePathPng(const std::string& path, const EsdfMap& esdf,
                         const explore::ExplorationResult& result, float z_m);

}  // namespace strata::apps
