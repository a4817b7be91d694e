#pragma once
// Summary statistics of per-frame measurements.
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

#include "json.h"

namespace strata::bench {

inline double mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + mid));
}

/// {"mean": .., "median": ..}
inline Json meanMedian(const std::vector<double>& values) {
  return Json::object().set("mean", mean(values)).set("median", median(values));
}

/// values[first, end) (empty when first >= size).
inline std::vector<double> tail(const std::vector<double>& values, std::size_t first) {
  if (first >= values.size()) return {};
  return std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(first), values.end());
}

}  // namespace strata::bench
