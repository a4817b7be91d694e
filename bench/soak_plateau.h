#pragma once
// Whether a soak's memory levels off: slopes and growth of the mapper's resident and device
// memory over the run, computed from its one-second samples. Pure functions, no I/O; the
// numbers are reported, never asserted.
#include <cstdint>
#include <string>
#include <vector>

namespace strata::bench {

/// One point per sample, all vectors the same length, time increasing.
struct SoakSeries {
  std::vector<double> t_s;
  std::vector<double> rss_mib;
  std::vector<double> hwm_mib;  // peak RSS, for the figure (the verdict does not use it)
  std::vector<double> device_mib;
  std::vector<std::int64_t> blocks;
};

struct PlateauVerdict {
  double warmup_end_s = 0.0;  // input: end of the first loop over the sessions
  double end_s = 0.0;
  /// Least-squares RSS slope over the second half of the run.
  double rss_slope_last_half_mib_per_min = 0.0;
  /// Mean RSS over the first and the last third of [warmup_end_s, end_s], and their difference.
  double rss_first_third_mib = 0.0;
  double rss_last_third_mib = 0.0;
  double rss_growth_thirds_mib = 0.0;
  /// The map stops growing at its last new maximum of blocks; device memory from then on.
  double map_stable_since_s = 0.0;
  std::int64_t map_blocks_max = 0;
  double device_at_map_stable_mib = 0.0;
  double device_end_mib = 0.0;
  double device_growth_after_map_stable_mib = 0.0;
  double device_slope_after_map_stable_mib_per_min = 0.0;
  /// A reading aid: RSS slope below kPlateauSlopeMibPerMin and device growth after the map
  /// stopped growing below kPlateauDeviceGrowthMib.
  bool plateau = false;
};

/// Below this many MiB/min over the second half, RSS counts as level (allocator noise, caches
/// filling: a leak of one frame's buffers per session would show well above it).
inline constexpr double kPlateauSlopeMibPerMin = 1.0;
inline constexpr double kPlateauDeviceGrowthMib = 1.0;

/// Zeros for fewer than 2 samples.
PlateauVerdict plateauVerdict(const SoakSeries& series, double warmup_end_s);

/// Least-squares slope of y over x, per unit of x; 0 with fewer than 2 distinct x.
double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y);

/// One paragraph with the numbers, for the console.
std::string describePlateau(const PlateauVerdict& verdict);

}  // namespace strata::bench
