#include "strata/repeat/truth_checker.h"

#include <cmath>

namespace strata::repeat {

TruthChecker::TruthChecker(const sim::WorldScene& scene, float step_m, float max_distance_m)
    : scene_(scene), step_m_(step_m), max_distance_m_(max_distance_m) {}

std::vector<std::uint8_t> TruthChecker::spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                                    float radius_m, UnknownPolicy /*unknown*/) {
  std::vector<std::uint8_t> free(centres_W.size(), 0);
  spheres_tested_ += centres_W.size();
  if (!(radius_m >= 0.0f) || radius_m > max_distance_m_) return free;
  for (std::size_t i = 0; i < centres_W.size(); ++i) {
    if (!centres_W[i].allFinite()) continue;
    free[i] = scene_.signedDistance(centres_W[i]) >= radius_m ? 1 : 0;
  }
  return free;
}

std::vector<EsdfSample> TruthChecker::sample(const std::vector<Eigen::Vector3f>& points_W) {
  std::vector<EsdfSample> out(points_W.size());
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    out[i].distance_m = scene_.signedDistance(points_W[i]);
    out[i].status = EsdfStatus::kKnown;
  }
  return out;
}

}  // namespace strata::repeat
