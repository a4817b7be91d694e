#pragma once
// The size prefilter that keeps matching sub-linear in the database size: models are kept sorted
// by their largest extent; a segment is only registered against models whose largest extent lies
// within [segment / max_ratio, segment * max_ratio] (binary search: O(log n + k)) and whose mean
// colour lies within max_color_distance (a model seen from one side still has its colour).
// Partial views shrink extents, so the ratio is generous; the consistency check decides.
// Thread safety: not thread safe for concurrent update and query.
#include <Eigen/Core>
#include <vector>

namespace strata::objects {

struct PrefilterConfig {
  float max_extent_ratio = 1.8f;
  float max_color_distance = 60.0f;  // Euclidean, 0..255 per channel; 0 disables colour
  void validate() const;
};

class ModelPrefilter {
 public:
  explicit ModelPrefilter(const PrefilterConfig& config = {});
  /// Adds or updates the descriptor of model `id`.
  void upsert(int id, const Eigen::Vector3f& extent_m, const Eigen::Vector3f& mean_color);
  /// Forgets model `id` (nothing when absent).
  void remove(int id);
  /// Ids of the models a segment with these descriptors may match, nearest extent first.
  std::vector<int> candidates(const Eigen::Vector3f& extent_m,
                              const Eigen::Vector3f& mean_color) const;
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    float max_extent_m;
    int id;
    Eigen::Vector3f extent_m;
    Eigen::Vector3f color;
  };
  PrefilterConfig config_;
  std::vector<Entry> entries_;  // sorted by max_extent_m
};

}  // namespace strata::objects
