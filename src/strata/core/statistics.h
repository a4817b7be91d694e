#pragma once
// Order statistics of samples (timings, errors) for reports and benchmarks.
// Thread safety: plain functions of their arguments.
#include <vector>

namespace strata {

/// The q-quantile (q in [0, 1], clamped) of the finite values, interpolated linearly between
/// neighbouring order statistics (q = 0.5 of an even count: the mean of the middle two).
/// Non-finite values are ignored; NaN when no finite value is left.
double quantile(std::vector<double> values, double q);

/// quantile(values, 0.5).
double median(std::vector<double> values);

/// The arithmetic mean of the finite values; NaN when there is none.
double mean(const std::vector<double>& values);

}  // namespace strata
