#include "soak_plateau.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace strata::bench {
namespace {

constexpr double kSecondsPerMinute = 60.0;

/// Mean of y over samples with t in [from_s, to_s]; 0 when none.
double meanBetween(const SoakSeries& s, const std::vector<double>& y, double from_s, double to_s) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.t_s.size(); ++i) {
    if (s.t_s[i] < from_s || s.t_s[i] > to_s) continue;
    sum += y[i];
    ++n;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

/// Slope of y over samples with t >= from_s, per minute.
double slopeFromPerMinute(const SoakSeries& s, const std::vector<double>& y, double from_s) {
  std::vector<double> x_part, y_part;
  for (std::size_t i = 0; i < s.t_s.size(); ++i) {
    if (s.t_s[i] < from_s) continue;
    x_part.push_back(s.t_s[i]);
    y_part.push_back(y[i]);
  }
  return leastSquaresSlope(x_part, y_part) * kSecondsPerMinute;
}

/// Index of the sample where blocks last reached a new maximum.
std::size_t lastNewBlockMaximum(const SoakSeries& s) {
  std::size_t at = 0;
  for (std::size_t i = 1; i < s.blocks.size(); ++i) {
    if (s.blocks[i] > s.blocks[at]) at = i;
  }
  return at;
}

}  // namespace

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0.0;
  double mean_x = 0.0, mean_y = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean_x += x[i] / n, mean_y += y[i] / n;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (x[i] - mean_x) * (y[i] - mean_y);
    sxx += (x[i] - mean_x) * (x[i] - mean_x);
  }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

PlateauVerdict plateauVerdict(const SoakSeries& s, double warmup_end_s) {
  PlateauVerdict v;
  v.warmup_end_s = warmup_end_s;
  if (s.t_s.size() < 2) return v;
  v.end_s = s.t_s.back();
  v.rss_slope_last_half_mib_per_min = slopeFromPerMinute(s, s.rss_mib, 0.5 * v.end_s);
  const double third_s = (v.end_s - warmup_end_s) / 3.0;
  v.rss_first_third_mib = meanBetween(s, s.rss_mib, warmup_end_s, warmup_end_s + third_s);
  v.rss_last_third_mib = meanBetween(s, s.rss_mib, v.end_s - third_s, v.end_s);
  v.rss_growth_thirds_mib = v.rss_last_third_mib - v.rss_first_third_mib;
  const std::size_t stable = lastNewBlockMaximum(s);
  v.map_stable_since_s = s.t_s[stable];
  v.map_blocks_max = s.blocks[stable];
  v.device_at_map_stable_mib = s.device_mib[stable];
  v.device_end_mib = s.device_mib.back();
  v.device_growth_after_map_stable_mib = v.device_end_mib - v.device_at_map_stable_mib;
  v.device_slope_after_map_stable_mib_per_min =
      slopeFromPerMinute(s, s.device_mib, v.map_stable_since_s);
  v.plateau = std::abs(v.rss_slope_last_half_mib_per_min) < kPlateauSlopeMibPerMin &&
              std::abs(v.device_growth_after_map_stable_mib) < kPlateauDeviceGrowthMib;
  return v;
}

std::string describePlateau(const PlateauVerdict& v) {
  char text[640];
  std::snprintf(text, sizeof(text),
                "RSS slope over the second half %+.2f MiB/min; after warm-up (%.0f s) the last "
                "third averaged %.1f MiB against %.1f MiB in the first (%+.1f MiB). The map "
                "stopped growing at %.0f s (%lld blocks); device memory then %.1f MiB, at the "
                "end %.1f MiB (%+.1f MiB, %+.2f MiB/min). Verdict: %s.",
                v.rss_slope_last_half_mib_per_min, v.warmup_end_s, v.rss_last_third_mib,
                v.rss_first_third_mib, v.rss_growth_thirds_mib, v.map_stable_since_s,
                static_cast<long long>(v.map_blocks_max), v.device_at_map_stable_mib,
                v.device_end_mib, v.device_growth_after_map_stable_mib,
                v.device_slope_after_map_stable_mib_per_min,
                v.plateau ? "memory levels off" : "memory still grows");
  return text;
}

}  // namespace strata::bench
