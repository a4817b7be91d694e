#include "strata/objects/object_prefilter.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "strata/core/error.h"

namespace strata::objects {
namespace {

// Extents below this (m) count as this much, so a nearly flat side still compares by ratio.
constexpr float kMinExtentM = 1e-3f;

/// How far apart two sorted extents are: the summed |log ratio| of their three edges.
float extentDistance(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  float d = 0.0f;
  for (int k = 0; k < 3; ++k) {
    d += std::abs(std::log(std::max(a[k], kMinExtentM) / std::max(b[k], kMinExtentM)));
  }
  return d;
}

void requireDescriptor(const Eigen::Vector3f& extent_m, const Eigen::Vector3f& color) {
  if (!extent_m.allFinite() || (extent_m.array() < 0.0f).any()) {
    throw InputError("model prefilter: extent_m must be finite and >= 0");
  }
  if (!color.allFinite()) throw InputError("model prefilter: mean colour must be finite");
}

}  // namespace

void PrefilterConfig::validate() const {
  if (!std::isfinite(max_extent_ratio) || max_extent_ratio < 1.0f) {
    throw InputError("invalid prefilter config: max_extent_ratio must be >= 1");
  }
  if (!std::isfinite(max_color_distance) || max_color_distance < 0.0f) {
    throw InputError("invalid prefilter config: max_color_distance must be >= 0 (0 disables)");
  }
}

ModelPrefilter::ModelPrefilter(const PrefilterConfig& config) : config_(config) {
  config_.validate();
}

void ModelPrefilter::remove(int id) {
  entries_.erase(
      std::remove_if(entries_.begin(), entries_.end(), [id](const Entry& e) { return e.id == id; }),
      entries_.end());
}

void ModelPrefilter::upsert(int id, const Eigen::Vector3f& extent_m,
                            const Eigen::Vector3f& mean_color) {
  requireDescriptor(extent_m, mean_color);
  entries_.erase(
      std::remove_if(entries_.begin(), entries_.end(), [id](const Entry& e) { return e.id == id; }),
      entries_.end());
  const Entry entry{extent_m.maxCoeff(), id, extent_m, mean_color};
  const auto at =
      std::upper_bound(entries_.begin(), entries_.end(), entry, [](const Entry& a, const Entry& b) {
        return std::tie(a.max_extent_m, a.id) < std::tie(b.max_extent_m, b.id);
      });
  entries_.insert(at, entry);
}

std::vector<int> ModelPrefilter::candidates(const Eigen::Vector3f& extent_m,
                                            const Eigen::Vector3f& mean_color) const {
  requireDescriptor(extent_m, mean_color);
  const float largest = extent_m.maxCoeff();
  const float lo = largest / config_.max_extent_ratio, hi = largest * config_.max_extent_ratio;
  const auto first = std::lower_bound(entries_.begin(), entries_.end(), lo,
                                      [](const Entry& e, float v) { return e.max_extent_m < v; });
  const auto last = std::upper_bound(first, entries_.end(), hi,
                                     [](float v, const Entry& e) { return v < e.max_extent_m; });
  std::vector<std::pair<float, int>> kept;
  for (auto it = first; it != last; ++it) {
    if (config_.max_color_distance > 0.0f &&
        (it->color - mean_color).norm() > config_.max_color_distance) {
      continue;
    }
    kept.emplace_back(extentDistance(it->extent_m, extent_m), it->id);
  }
  std::sort(kept.begin(), kept.end());
  std::vector<int> ids;
  ids.reserve(kept.size());
  for (const auto& k : kept) ids.push_back(k.second);
  return ids;
}

}  // namespace strata::objects
