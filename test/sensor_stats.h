#pragma once
// Sample mean and standard deviation for the sensor tests' statistical checks.
#include <cmath>
#include <cstddef>
#include <vector>

namespace strata::sim::test {

struct Stats {
  double mean = 0.0, stddev = 0.0;
  std::size_t count = 0;
};

inline Stats statsOf(const std::vector<double>& values) {
  Stats s;
  s.count = values.size();
  for (double v : values) s.mean += v;
  s.mean /= static_cast<double>(values.size());
  for (double v : values) s.stddev += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(s.stddev / static_cast<double>(values.size() - 1));
  return s;
}

}  // namespace strata::sim::test
