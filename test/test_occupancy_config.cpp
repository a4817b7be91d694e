// Occupancy layer: OccupancyConfig's defaults (OctoMap's published ones) and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/occupancy/occupancy_device.h"

namespace strata {
namespace {

MapConfig mapConfig() {
  MapConfig config;
  config.voxel_size_m = 0.05f;
  config.max_depth_m = 6.0f;
  return config;
}

TEST(OccupancyConfig, DefaultsAreOctoMapsPublishedOnes) {
  const OccupancyConfig config = OccupancyConfig::forMap(mapConfig());
  EXPECT_NO_THROW(config.validate());
  EXPECT_FLOAT_EQ(config.max_range_m, 6.0f);
  const OccupancyLogOdds l = config.logOdds();
  EXPECT_NEAR(l.hit, std::log(0.7 / 0.3), 1e-5);  // the probabilities are floats
  EXPECT_NEAR(l.miss, std::log(0.4 / 0.6), 1e-5);
  EXPECT_NEAR(l.min, std::log(0.12 / 0.88), 1e-5);
  EXPECT_NEAR(l.max, std::log(0.97 / 0.03), 1e-5);
  EXPECT_EQ(l.occupied, 0.0f);
}

void expectRejected(OccupancyConfig config, const std::string& field) {
  try {
    config.validate();
    ADD_FAILURE() << "accepted a bad " << field;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(OccupancyConfig, BadConfigIsRejectedNamingTheField) {
  OccupancyConfig c;
  c.prob_hit = 0.4f;  // a hit would lower occupancy
  expectRejected(c, "prob_hit");
  c = {};
  c.prob_miss = 0.6f;
  expectRejected(c, "prob_miss");
  c = {};
  c.clamp_min_prob = 0.98f;
  expectRejected(c, "clamp_min_prob");
  c = {};
  c.clamp_max_prob = 1.0f;
  expectRejected(c, "clamp_max_prob");
  c = {};
  c.occupied_prob = 0.1f;  // below the lower clamp: nothing could ever be free
  expectRejected(c, "occupied_prob");
  c = {};
  c.max_range_m = std::nanf("");
  expectRejected(c, "max_range_m");
  c = {};
  c.pixel_stride = 0;
  expectRejected(c, "pixel_stride");
  c = {};
  c.prob_hit = 0.0f;
  DeviceTsdfMap map(test::sharedContext(), mapConfig());
  EXPECT_THROW(DeviceOccupancy(map, c), InputError);
  EXPECT_EQ(map.labelLayerCount(), 0);  // rejected before the map changed
}

}  // namespace
}  // namespace strata
