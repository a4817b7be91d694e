#include "strata/core/statistics.h"
#include "strata/trajectory/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "strata/core/error.h"

namespace strata::trajectory {
namespace {

bool finitePose(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

struct Matches {
  std::vector<double> timestamps_s;
  std::vector<Eigen::Isometry3d> estimate, truth;
};

Matches associate(const std::vector<StampedPose>& estimate, const std::vector<StampedPose>& truth,
                  double max_time_difference_s) {
  std::vector<double> truth_s;
  truth_s.reserve(truth.size());
  for (const StampedPose& p : truth) truth_s.push_back(p.timestamp_s);
  Matches m;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    if (!finitePose(estimate[i].T_W_C)) {
      throw InputError("estimated pose " + std::to_string(i) +
                       " (t = " + std::to_string(estimate[i].timestamp_s) + " s) is not finite");
    }
    const auto k = tum::nearestWithin(truth_s, estimate[i].timestamp_s, max_time_difference_s);
    if (!k) continue;
    if (!finitePose(truth[*k].T_W_C)) {
      throw InputError("true pose at t = " + std::to_string(truth[*k].timestamp_s) +
                       " s is not finite");
    }
    m.timestamps_s.push_back(estimate[i].timestamp_s);
    m.estimate.push_back(estimate[i].T_W_C);
    m.truth.push_back(truth[*k].T_W_C);
  }
  return m;
}

void fillAte(const Matches& m, TrajectoryError* e) {
  double sq = 0.0, sum = 0.0, rot_sq = 0.0;
  for (std::size_t i = 0; i < m.estimate.size(); ++i) {
    const Eigen::Isometry3d T_gt_C = e->aligned.apply(m.estimate[i]);
    const double d = (T_gt_C.translation() - m.truth[i].translation()).norm();
    const double angle =
        Eigen::AngleAxisd(m.truth[i].linear().transpose() * T_gt_C.linear()).angle();
    e->estimate_positions_m.push_back(T_gt_C.translation());
    e->truth_positions_m.push_back(m.truth[i].translation());
    e->position_errors_m.push_back(d);
    sq += d * d;
    sum += d;
    rot_sq += angle * angle;
    e->ate_max_m = std::max(e->ate_max_m, d);
  }
  const double n = static_cast<double>(m.estimate.size());
  e->ate_rmse_m = std::sqrt(sq / n);
  e->ate_mean_m = sum / n;
  e->ate_median_m = median(e->position_errors_m);
  e->rotation_rmse_deg = std::sqrt(rot_sq / n) * 180.0 / M_PI;
}

}  // namespace

TrajectoryError evaluateTrajectory(const std::vector<StampedPose>& estimate,
                                   const std::vector<StampedPose>& truth,
                                   const TrajectoryErrorOptions& options) {
  if (!(options.rpe_segment_m > 0.0)) throw InputError("RPE segment length must be positive");
  const Matches m = associate(estimate, truth, options.max_time_difference_s);
  if (m.estimate.empty()) {
    throw InputError("no estimated pose (of " + std::to_string(estimate.size()) +
                     ") has a true pose within " + std::to_string(options.max_time_difference_s) +
                     " s of its timestamp");
  }
  TrajectoryError e;
  e.estimated = estimate.size();
  e.matched = m.estimate.size();
  e.duration_s = m.timestamps_s.back() - m.timestamps_s.front();
  for (std::size_t i = 1; i < m.truth.size(); ++i) {
    e.path_length_m += (m.truth[i].translation() - m.truth[i - 1].translation()).norm();
  }
  e.alignment = options.alignment;
  e.aligned = alignTrajectory(m.estimate, m.truth, options.alignment);
  e.scale = e.aligned.scale;
  e.timestamps_s = m.timestamps_s;
  fillAte(m, &e);
  e.rpe_segment_m = options.rpe_segment_m;
  relativePoseError(m.estimate, m.truth, options.rpe_segment_m, e.scale, &e.rpe_pairs,
                    &e.rpe_trans_percent, &e.rpe_rot_deg_per_m);
  return e;
}

TrajectoryError evaluateTrajectory(const std::vector<StampedPose>& estimate,
                                   const std::vector<StampedPose>& truth, Alignment alignment,
                                   double max_time_difference_s) {
  TrajectoryErrorOptions options;
  options.alignment = alignment;
  options.max_time_difference_s = max_time_difference_s;
  return evaluateTrajectory(estimate, truth, options);
}

std::string trajectoryErrorJson(const TrajectoryError& e) {
  using Json = nlohmann::ordered_json;
  Json j;
  j["alignment"] = alignmentName(e.alignment);
  j["estimated"] = e.estimated;
  j["matched"] = e.matched;
  j["duration_s"] = e.duration_s;
  j["path_length_m"] = e.path_length_m;
  j["scale"] = e.scale;
  j["ate_rmse_m"] = e.ate_rmse_m;
  j["ate_mean_m"] = e.ate_mean_m;
  j["ate_median_m"] = e.ate_median_m;
  j["ate_max_m"] = e.ate_max_m;
  j["ate_percent_of_path"] = e.path_length_m > 0.0 ? 100.0 * e.ate_rmse_m / e.path_length_m : NAN;
  j["rotation_rmse_deg"] = e.rotation_rmse_deg;
  j["rpe_segment_m"] = e.rpe_segment_m;
  j["rpe_pairs"] = e.rpe_pairs;
  j["rpe_trans_percent"] = e.rpe_trans_percent;
  j["rpe_rot_deg_per_m"] = e.rpe_rot_deg_per_m;
  return j.dump(2, ' ', false, Json::error_handler_t::replace);  // NaN as null
}

}  // namespace strata::trajectory
