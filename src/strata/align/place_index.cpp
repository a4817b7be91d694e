#include "strata/align/place_index.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "strata/align/internal/hamming.h"
#include "strata/core/error.h"

// NOTE: hnswlib's SSE path prefetches one entry past the end of a link list, a heap read out of
// bounds that AddressSanitizer stops on (known upstream, unfixed in Debian's 0.6.2). Its SSE code
// is that prefetching and the L2/inner-product kernels, which the Hamming space does not use.
#define NO_MANUAL_VECTORIZATION
#include <hnswlib/hnswlib.h>

namespace strata::align {
namespace {

// hnswlib's metric interface for 32-byte descriptors: distance = differing bits.
class HammingSpace : public hnswlib::SpaceInterface<int> {
 public:
  size_t get_data_size() override { return sizeof(Descriptor); }
  hnswlib::DISTFUNC<int> get_dist_func() override { return &distance; }
  void* get_dist_func_param() override { return nullptr; }

 private:
  static int distance(const void* a, const void* b, const void* /*param*/) {
    return detail::hammingDistance(a, b);
  }
};

constexpr std::size_t kInitialCapacity = 4096;

// (distance, descriptor label) of the k nearest indexed descriptors, any order.
using Neighbours = std::vector<std::pair<int, std::size_t>>;

Neighbours exactNeighbours(const std::vector<Descriptor>& indexed, const Descriptor& query,
                           std::size_t k) {
  Neighbours best;
  best.reserve(k + 1);
  for (std::size_t i = 0; i < indexed.size(); ++i) {
    const int d = detail::hammingDistance(indexed[i], query);
    if (best.size() == k && d >= best.back().first) continue;
    // Insertion into the short sorted list (k is a handful).
    auto at = std::upper_bound(best.begin(), best.end(), std::make_pair(d, i));
    best.insert(at, {d, i});
    if (best.size() > k) best.pop_back();
  }
  return best;
}

/// At most config.max_descriptors_per_keyframe descriptors, evenly strided through the list.
std::vector<Descriptor> sampled(const std::vector<Descriptor>& all, const PlaceIndexConfig& config) {
  const std::size_t limit = static_cast<std::size_t>(config.max_descriptors_per_keyframe);
  if (limit == 0 || all.size() <= limit) return all;
  std::vector<Descriptor> out;
  out.reserve(limit);
  for (std::size_t i = 0; i < limit; ++i) out.push_back(all[i * all.size() / limit]);
  return out;
}

}  // namespace

void PlaceIndexConfig::validate() const {
  if (max_descriptors_per_keyframe < 0) {
    throw InputError("PlaceIndexConfig: max_descriptors_per_keyframe must be >= 0 (0: all)");
  }
  if (neighbours < 1) throw InputError("PlaceIndexConfig: neighbours must be >= 1");
  if (max_hamming_distance < 0 || max_hamming_distance > 256) {
    throw InputError("PlaceIndexConfig: max_hamming_distance must be in [0, 256]");
  }
  if (hnsw_m < 2) throw InputError("PlaceIndexConfig: hnsw_m must be >= 2");
  if (hnsw_ef_construction < 1) {
    throw InputError("PlaceIndexConfig: hnsw_ef_construction must be >= 1");
  }
  if (hnsw_ef_search < 1) throw InputError("PlaceIndexConfig: hnsw_ef_search must be >= 1");
}

struct PlaceIndex::Impl {
  PlaceIndexConfig config;
  HammingSpace space;  // outlives hnsw, which keeps a pointer to it
  std::unique_ptr<hnswlib::HierarchicalNSW<int>> hnsw;
  std::vector<Descriptor> descriptors;                         // by label (the exact search's data)
  std::vector<std::size_t> keyframe_of;                        // by label
  std::unordered_map<std::size_t, std::size_t> feature_count;  // by keyframe

  Neighbours neighbours(const Descriptor& query) const {
    const auto k = static_cast<std::size_t>(config.neighbours);
    if (config.exact) return exactNeighbours(descriptors, query, k);
    Neighbours found;
    auto heap = hnsw->searchKnn(query.data(), k);
    for (; !heap.empty(); heap.pop()) found.emplace_back(heap.top().first, heap.top().second);
    return found;
  }

  void reserve(std::size_t count) {
    if (config.exact) return;
    const std::size_t needed = descriptors.size() + count;
    if (!hnsw) {
      hnsw = std::make_unique<hnswlib::HierarchicalNSW<int>>(
          &space, std::max(kInitialCapacity, needed), static_cast<std::size_t>(config.hnsw_m),
          static_cast<std::size_t>(config.hnsw_ef_construction));
      hnsw->setEf(static_cast<std::size_t>(config.hnsw_ef_search));
    } else if (needed > hnsw->max_elements_) {
      hnsw->resizeIndex(std::max(needed, 2 * hnsw->max_elements_));
    }
  }
};

PlaceIndex::PlaceIndex(const PlaceIndexConfig& config) : impl_(std::make_unique<Impl>()) {
  config.validate();
  impl_->config = config;
}

PlaceIndex::~PlaceIndex() = default;
PlaceIndex::PlaceIndex(PlaceIndex&&) noexcept = default;
PlaceIndex& PlaceIndex::operator=(PlaceIndex&&) noexcept = default;

void PlaceIndex::add(std::size_t keyframe, const KeyframeFeatures& features) {
  if (impl_->feature_count.count(keyframe) != 0) {
    throw InputError("PlaceIndex::add: keyframe " + std::to_string(keyframe) +
                     " is already in the index");
  }
  if (features.descriptors.size() != features.size()) {
    throw InputError("PlaceIndex::add: keyframe " + std::to_string(keyframe) + " has " +
                     std::to_string(features.size()) + " keypoints but " +
                     std::to_string(features.descriptors.size()) + " descriptors");
  }
  const std::vector<Descriptor> used = sampled(features.descriptors, impl_->config);
  impl_->reserve(used.size());
  for (const Descriptor& d : used) {
    const std::size_t label = impl_->descriptors.size();
    if (impl_->hnsw) impl_->hnsw->addPoint(d.data(), label);
    impl_->descriptors.push_back(d);
    impl_->keyframe_of.push_back(keyframe);
  }
  impl_->feature_count[keyframe] = used.size();
}

std::size_t PlaceIndex::keyframes() const { return impl_->feature_count.size(); }
std::size_t PlaceIndex::descriptors() const { return impl_->descriptors.size(); }

std::vector<PlaceCandidate> PlaceIndex::query(
    const KeyframeFeatures& features, std::size_t max_candidates, int min_votes,
    const std::function<bool(std::size_t)>& admissible) const {
  if (impl_->descriptors.empty() || features.descriptors.empty() || max_candidates == 0) return {};

  // Each query descriptor votes once for every keyframe among its near neighbours.
  std::unordered_map<std::size_t, int> votes;
  std::unordered_set<std::size_t> voted;
  const std::vector<Descriptor> used = sampled(features.descriptors, impl_->config);
  for (const Descriptor& d : used) {
    voted.clear();
    for (const auto& [distance, label] : impl_->neighbours(d)) {
      if (distance > impl_->config.max_hamming_distance) continue;
      const std::size_t keyframe = impl_->keyframe_of[label];
      if (voted.insert(keyframe).second) ++votes[keyframe];
    }
  }

  std::vector<PlaceCandidate> candidates;
  const double query_count = static_cast<double>(used.size());
  for (const auto& [keyframe, count] : votes) {
    if (count < min_votes || (admissible && !admissible(keyframe))) continue;
    const double indexed_count = static_cast<double>(impl_->feature_count.at(keyframe));
    candidates.push_back({keyframe, count, count / std::sqrt(query_count * indexed_count)});
  }
  // Highest score first; ties by the keyframe index so results do not depend on hash order.
  std::sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) {
    return x.score != y.score ? x.score > y.score : x.keyframe < y.keyframe;
  });
  if (candidates.size() > max_candidates) candidates.resize(max_candidates);
  return candidates;
}

}  // namespace strata::align
