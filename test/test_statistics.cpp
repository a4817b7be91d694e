// Order statistics shared by reports and benchmarks (core/statistics.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "strata/core/statistics.h"

namespace strata {
namespace {

TEST(Statistics, QuantilesInterpolateBetweenOrderStatistics) {
  const std::vector<double> v = {4.0, 1.0, 3.0, 2.0};  // sorted: 1 2 3 4
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 2.5);                // mean of the middle two
  EXPECT_DOUBLE_EQ(quantile(v, 0.95), 3.0 + 0.85 * 1.0);  // at 2.85 of 0..3
  EXPECT_DOUBLE_EQ(quantile(v, 2.0), 4.0);                // q clamped
  EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(mean({1.0, 2.0, 6.0}), 3.0);
}

TEST(Statistics, NonFiniteValuesAreIgnoredAndNothingLeftIsNan) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(median({nan, 2.0, inf, 4.0}), 3.0);
  EXPECT_DOUBLE_EQ(mean({nan, 2.0, -inf, 4.0}), 3.0);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
  EXPECT_TRUE(std::isnan(median({nan, inf})));
  EXPECT_TRUE(std::isnan(mean({})));
}

}  // namespace
}  // namespace strata
