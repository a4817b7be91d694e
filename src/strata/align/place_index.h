#pragma once
// Place recognition: which earlier keyframes may show the same place as a new one. An
// approximate nearest-neighbour index (hnswlib, HNSW graph, Hamming distance) over every
// keyframe's ORB descriptors; a query keyframe's descriptors vote for the keyframes of their
// nearest neighbours, and the candidates are ranked by votes normalised for the keyframes'
// feature counts. Why this and not a trained bag of words: docs/align.md.
// Thread safety: add() needs exclusive access; query() may run from several threads at once.
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "strata/align/keyframe_features.h"

namespace strata::align {

struct PlaceIndexConfig {
  int neighbours = 4;              // nearest descriptors per query descriptor
  int max_hamming_distance = 64;   // of 256 bits; farther neighbours do not vote
  int hnsw_m = 16;                 // HNSW graph degree
  int hnsw_ef_construction = 100;
  int hnsw_ef_search = 64;
  bool exact = false;              // brute-force search instead of HNSW (recall reference)
  /// Descriptors a keyframe adds and queries with, at most (an even stride through its list;
  /// 0: all). Voting needs a few hundred; each one more costs an HNSW search per query and a
  /// node in the graph (textured scenes give ORB's full 1000 per keyframe).
  int max_descriptors_per_keyframe = 300;
  void validate() const;
};

struct PlaceCandidate {
  std::size_t keyframe = 0;  // the caller's keyframe index given to add()
  int votes = 0;
  double score = 0.0;        // votes / sqrt(features of query * features of candidate)
};

class PlaceIndex {
 public:
  explicit PlaceIndex(const PlaceIndexConfig& config = {});
  ~PlaceIndex();
  PlaceIndex(PlaceIndex&&) noexcept;
  PlaceIndex& operator=(PlaceIndex&&) noexcept;

  /// Adds a keyframe's descriptors under the caller's index `keyframe` (unique; InputError when
  /// used twice).
  void add(std::size_t keyframe, const KeyframeFeatures& features);
  std::size_t keyframes() const;
  std::size_t descriptors() const;

  /// The best `max_candidates` keyframes for which `admissible(keyframe)` is true, by score,
  /// highest first. Keyframes with fewer than `min_votes` votes are not candidates.
  std::vector<PlaceCandidate> query(const KeyframeFeatures& features, std::size_t max_candidates,
                                    int min_votes,
                                    const std::function<bool(std::size_t)>& admissible) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strata::align
