#pragma once
// Summary statistics of per-frame measurements.
#include <cstddef>
#include <vector>

#include "strata/core/statistics.h"
#include "json.h"

namespace strata::bench {

// NaN (written as null) for no values.
using ::strata::mean;
using ::strata::median;

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
