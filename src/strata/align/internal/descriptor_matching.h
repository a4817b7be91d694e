#pragma once
// Descriptor matches between two keyframes: mutual nearest neighbours (Hamming) that pass the
// ratio test and a distance gate. Exact (every pair compared): keyframes hold about a thousand.
#include <utility>
#include <vector>

#include "strata/align/keyframe_features.h"

namespace strata::align::detail {

/// (index in a, index in b) pairs, by increasing index in b.
std::vector<std::pair<int, int>> matchDescriptors(const std::vector<Descriptor>& a,
                                                  const std::vector<Descriptor>& b,
                                                  float ratio_test, int max_hamming_distance);

}  // namespace strata::align::detail
