// The soak's plateau verdict: slopes and growth from one-second samples, on series whose answer
// is known (level, leaking, a map that stops growing).
#include <gtest/gtest.h>

#include "soak_plateau.h"

namespace strata::bench {
namespace {

/// `seconds` samples: RSS = 500 MiB + leak per minute, the map growing for `growth_s`, device
/// memory following the map (plus `device_leak_mib_per_min` throughout).
SoakSeries series(int seconds, double rss_leak_mib_per_min, double growth_s,
                  double device_leak_mib_per_min) {
  SoakSeries s;
  for (int i = 0; i <= seconds; ++i) {
    const double t = i, minutes = t / 60.0;
    s.t_s.push_back(t);
    s.rss_mib.push_back(500.0 + rss_leak_mib_per_min * minutes);
    s.hwm_mib.push_back(s.rss_mib.back());
    const std::int64_t blocks = static_cast<std::int64_t>(std::min(t, growth_s) * 10.0);
    s.blocks.push_back(blocks);
    s.device_mib.push_back(100.0 + 0.01 * blocks + device_leak_mib_per_min * minutes);
  }
  return s;
}

TEST(SoakPlateau, LeastSquaresSlopeOfALine) {
  EXPECT_DOUBLE_EQ(leastSquaresSlope({0, 1, 2, 3}, {1, 3, 5, 7}), 2.0);
  EXPECT_DOUBLE_EQ(leastSquaresSlope({1}, {5}), 0.0) << "one point has no slope";
  EXPECT_DOUBLE_EQ(leastSquaresSlope({2, 2}, {1, 5}), 0.0) << "no spread in x";
}

TEST(SoakPlateau, LevelMemoryIsAPlateau) {
  const PlateauVerdict v = plateauVerdict(series(600, 0.0, 100.0, 0.0), 100.0);
  EXPECT_NEAR(v.rss_slope_last_half_mib_per_min, 0.0, 1e-9);
  EXPECT_NEAR(v.rss_growth_thirds_mib, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(v.map_stable_since_s, 100.0);
  EXPECT_EQ(v.map_blocks_max, 1000);
  EXPECT_NEAR(v.device_growth_after_map_stable_mib, 0.0, 1e-9);
  EXPECT_TRUE(v.plateau);
}

TEST(SoakPlateau, AHostLeakShowsInSlopeAndThirds) {
  const PlateauVerdict v = plateauVerdict(series(600, 6.0, 100.0, 0.0), 0.0);
  EXPECT_NEAR(v.rss_slope_last_half_mib_per_min, 6.0, 1e-6);
  // Thirds of 10 minutes: their means sit at 100 s and 500 s, 400 s apart at 6 MiB/min.
  EXPECT_NEAR(v.rss_growth_thirds_mib, 40.0, 0.5);
  EXPECT_FALSE(v.plateau);
}

TEST(SoakPlateau, DeviceGrowthCountsOnlyAfterTheMapStopped) {
  const PlateauVerdict level = plateauVerdict(series(600, 0.0, 300.0, 0.0), 0.0);
  EXPECT_NEAR(level.device_growth_after_map_stable_mib, 0.0, 1e-9)
      << "device memory that follows the map is not a leak";
  const PlateauVerdict leak = plateauVerdict(series(600, 0.0, 300.0, 2.0), 0.0);
  EXPECT_NEAR(leak.device_growth_after_map_stable_mib, 10.0, 1e-6);
  EXPECT_NEAR(leak.device_slope_after_map_stable_mib_per_min, 2.0, 1e-6);
  EXPECT_FALSE(leak.plateau);
}

TEST(SoakPlateau, TooFewSamplesGiveZeros) {
  SoakSeries one;
  one.t_s = {0.0};
  one.rss_mib = one.hwm_mib = one.device_mib = {1.0};
  one.blocks = {1};
  const PlateauVerdict v = plateauVerdict(one, 0.0);
  EXPECT_EQ(v.end_s, 0.0);
  EXPECT_FALSE(v.plateau);
}

}  // namespace
}  // namespace strata::bench
