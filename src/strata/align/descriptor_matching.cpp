#include "strata/align/internal/descriptor_matching.h"

#include <limits>

#include "strata/align/internal/hamming.h"

namespace strata::align::detail {
namespace {

struct Nearest {
  int index = -1;
  int best = std::numeric_limits<int>::max();
  int second = std::numeric_limits<int>::max();

  void offer(int candidate, int distance) {
    if (distance < best) {
      second = best;
      best = distance;
      index = candidate;
    } else if (distance < second) {
      second = distance;
    }
  }
};

}  // namespace

std::vector<std::pair<int, int>> matchDescriptors(const std::vector<Descriptor>& a,
                                                  const std::vector<Descriptor>& b,
                                                  float ratio_test, int max_hamming_distance) {
  std::vector<Nearest> nearest_in_a(b.size());
  std::vector<Nearest> nearest_in_b(a.size());
  for (std::size_t j = 0; j < b.size(); ++j) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const int d = hammingDistance(a[i], b[j]);
      nearest_in_a[j].offer(static_cast<int>(i), d);
      nearest_in_b[i].offer(static_cast<int>(j), d);
    }
  }
  std::vector<std::pair<int, int>> matches;
  for (std::size_t j = 0; j < b.size(); ++j) {
    const Nearest& n = nearest_in_a[j];
    if (n.index < 0 || n.best > max_hamming_distance) continue;
    // A second neighbour that is missing counts as infinitely far: the match is unambiguous.
    if (n.second != std::numeric_limits<int>::max() &&
        static_cast<float>(n.best) >= ratio_test * static_cast<float>(n.second)) {
      continue;
    }
    if (nearest_in_b[static_cast<std::size_t>(n.index)].index != static_cast<int>(j)) continue;
    matches.emplace_back(n.index, static_cast<int>(j));
  }
  return matches;
}

}  // namespace strata::align::detail
