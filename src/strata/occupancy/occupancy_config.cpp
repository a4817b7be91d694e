#include "strata/occupancy/occupancy_config.h"

#include <cmath>
#include <sstream>

#include "strata/core/error.h"

namespace strata {
namespace {

[[noreturn]] void reject(const std::string& field, double value, const char* rule) {
  std::ostringstream msg;
  msg << "invalid occupancy config: " << field << " = " << value << " " << rule;
  throw InputError(msg.str());
}

void requireProbability(float p, const char* field) {
  if (!std::isfinite(p) || p <= 0.0f || p >= 1.0f) reject(field, p, "must lie in (0, 1)");
}

}  // namespace

OccupancyConfig OccupancyConfig::forMap(const MapConfig& map) {
  OccupancyConfig config;
  config.min_depth_m = map.min_depth_m;
  config.max_range_m = map.max_depth_m;
  return config;
}

void OccupancyConfig::validate() const {
  requireProbability(prob_hit, "prob_hit");
  requireProbability(prob_miss, "prob_miss");
  requireProbability(clamp_min_prob, "clamp_min_prob");
  requireProbability(clamp_max_prob, "clamp_max_prob");
  requireProbability(occupied_prob, "occupied_prob");
  // A hit must raise and a miss lower the occupancy, or the map never converges.
  if (prob_hit <= 0.5f) reject("prob_hit", prob_hit, "must exceed 0.5 (a hit raises occupancy)");
  if (prob_miss >= 0.5f) reject("prob_miss", prob_miss, "must be below 0.5 (a miss lowers it)");
  if (clamp_min_prob >= clamp_max_prob) {
    reject("clamp_min_prob", clamp_min_prob, "must be below clamp_max_prob");
  }
  // Outside the clamping range a voxel could never change class.
  if (occupied_prob <= clamp_min_prob || occupied_prob >= clamp_max_prob) {
    reject("occupied_prob", occupied_prob, "must lie strictly between the clamping thresholds");
  }
  if (!std::isfinite(min_depth_m) || min_depth_m < 0.0f) {
    reject("min_depth_m", min_depth_m, "must be finite and >= 0");
  }
  if (!std::isfinite(max_range_m) || max_range_m <= min_depth_m) {
    reject("max_range_m", max_range_m, "must be finite and above min_depth_m");
  }
  if (pixel_stride == 0 || pixel_stride > 64) {
    reject("pixel_stride", pixel_stride, "must be in [1, 64]");
  }
}

float logOddsOf(double probability) {
  return static_cast<float>(std::log(probability / (1.0 - probability)));
}

OccupancyLogOdds OccupancyConfig::logOdds() const {
  OccupancyLogOdds l;
  l.hit = logOddsOf(prob_hit);
  l.miss = logOddsOf(prob_miss);
  l.min = logOddsOf(clamp_min_prob);
  l.max = logOddsOf(clamp_max_prob);
  l.occupied = logOddsOf(occupied_prob);
  return l;
}

std::string OccupancyConfig::describe() const {
  std::ostringstream out;
  out << "P(hit)=" << prob_hit << " P(miss)=" << prob_miss << " clamp=[" << clamp_min_prob << ", "
      << clamp_max_prob << "] occupied>=" << occupied_prob << " depth=[" << min_depth_m << ", "
      << max_range_m << "] m stride=" << pixel_stride;
  return out.str();
}

}  // namespace strata
