// View gain: the device kernel against its C++ reference (equal by construction: the same
// fixed-point march and integer volumes), and both against what the maps imply: the exact fan
// volume on an empty map, nothing behind an observed wall, the unobserved half of a room.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "strata/core/error.h"
#include "strata/explore/view_gain.h"
#include "fusion_fixture.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::explore {
namespace {

constexpr float kVoxel_m = 0.1f;
constexpr double kTwoPi = 2.0 * M_PI;

MapConfig mapConfig() {
  MapConfig config;
  config.voxel_size_m = kVoxel_m;
  return config;
}

/// Fills every voxel whose centre lies in [lo, hi] with what `voxel_at` says (weight 0 = leave).
using VoxelFn = std::function<TsdfVoxel(const Eigen::Vector3f&)>;
void fillBox(TsdfMap& map, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
             const VoxelFn& voxel_at) {
  const Eigen::Vector3i a = (lo / kVoxel_m).array().floor().cast<int>();
  const Eigen::Vector3i b = (hi / kVoxel_m).array().floor().cast<int>();
  for (int z = a.z(); z <= b.z(); ++z) {
    for (int y = a.y(); y <= b.y(); ++y) {
      for (int x = a.x(); x <= b.x(); ++x) {
        const GlobalVoxelIndex v(x, y, z);
        const TsdfVoxel voxel = voxel_at(voxelCenter(v, kVoxel_m));
        if (voxel.weight > 0.0f) map.allocateVoxel(v) = voxel;
      }
    }
  }
}

std::vector<ViewGain> onDevice(const TsdfMap& map, const ViewGainConfig& config,
                               const std::vector<Eigen::Vector3f>& positions) {
  DeviceTsdfMap device(test::sharedContext(), map.config());
  device.upload(map);
  ViewGainKernel kernel(test::sharedContext(), config);
  return kernel.run(device, positions);
}

void expectEqualGains(const std::vector<ViewGain>& device, const std::vector<ViewGain>& reference) {
  ASSERT_EQ(device.size(), reference.size());
  for (std::size_t i = 0; i < device.size(); ++i) {
    SCOPED_TRACE("position " + std::to_string(i));
    EXPECT_EQ(device[i].bin_gain_m3, reference[i].bin_gain_m3);
    EXPECT_EQ(device[i].best_yaw_rad, reference[i].best_yaw_rad);
    EXPECT_EQ(device[i].best_gain_m3, reference[i].best_gain_m3);
  }
}

double fanVolume_m3(const ViewGainConfig& c, double yaw_span_rad) {
  const double r0 = c.min_range_m, r1 = c.max_range_m;
  return yaw_span_rad * 2.0 * std::sin(0.5 * c.vertical_fov_rad) * (r1 * r1 * r1 - r0 * r0 * r0) /
         3.0;
}

TEST(ViewGain, EmptyMapSeesTheWholeFan) {
  const TsdfMap map(mapConfig());
  ViewGainConfig config;
  const std::vector<Eigen::Vector3f> positions = {{0.0f, 0.0f, 1.0f}, {-3.33f, 7.01f, 0.42f}};
  const std::vector<ViewGain> reference = viewGainReference(map, config, positions);
  expectEqualGains(onDevice(map, config, positions), reference);
  const double bin_m3 = fanVolume_m3(config, kTwoPi / config.yaw_bins);
  for (const ViewGain& gain : reference) {
    for (float g : gain.bin_gain_m3) EXPECT_NEAR(g, bin_m3, 1e-4 * bin_m3);
    EXPECT_NEAR(gain.best_gain_m3, fanVolume_m3(config, config.horizontal_fov_rad), 1e-3);
  }
}

TEST(ViewGain, RaysReachTheirRange) {
  // Observed free space within 2 m of the position, unknown beyond: each bin gains the fan's
  // volume between 2 m and max_range (up to the voxels on the sphere).
  const Eigen::Vector3f p(0.31f, -0.22f, 1.07f);
  TsdfMap map(mapConfig());
  fillBox(map, p.array() - 2.2f, p.array() + 2.2f, [&](const Eigen::Vector3f& c) {
    TsdfVoxel voxel;
    voxel.tsdf_m = 0.3f;
    voxel.weight = (c - p).norm() < 2.0f ? 1.0f : 0.0f;
    return voxel;
  });
  ViewGainConfig config;
  const std::vector<ViewGain> reference = viewGainReference(map, config, {p});
  expectEqualGains(onDevice(map, config, {p}), reference);
  ViewGainConfig beyond = config;
  beyond.min_range_m = 2.0f;
  const double bin_m3 = fanVolume_m3(beyond, kTwoPi / config.yaw_bins);
  for (float g : reference[0].bin_gain_m3) EXPECT_NEAR(g, bin_m3, 0.03 * bin_m3);
}

/// A wall at x = 2 observed from the side x < 2; everything at x < -0.5 unobserved.
TsdfMap wallMap() {
  TsdfMap map(mapConfig());
  fillBox(map, {-0.5f, -6.0f, -2.0f}, {2.3f, 6.0f, 4.0f}, [](const Eigen::Vector3f& p) {
    TsdfVoxel voxel;
    voxel.tsdf_m = std::clamp(2.0f - p.x(), -0.3f, 0.3f);
    voxel.weight = 5.0f;
    return voxel;
  });
  return map;
}

TEST(ViewGain, NothingToGainTowardsAnObservedWall) {
  const TsdfMap map = wallMap();
  ViewGainConfig config;
  const std::vector<Eigen::Vector3f> positions = {{0.0f, 0.0f, 1.0f}, {0.5f, 1.0f, 1.2f}};
  const std::vector<ViewGain> reference = viewGainReference(map, config, positions);
  expectEqualGains(onDevice(map, config, positions), reference);
  for (const ViewGain& gain : reference) {
    const float towards = gainAtYaw(gain, config, 0.0f);
    const float away = gainAtYaw(gain, config, float(M_PI));
    EXPECT_LT(towards, 1e-3f);
    EXPECT_GT(away, 0.2f * fanVolume_m3(config, config.horizontal_fov_rad));
    EXPECT_LT(std::abs(gain.best_yaw_rad - float(M_PI)), 0.25f) << gain.best_yaw_rad;
    // best_gain is the largest window gain over all yaws.
    EXPECT_FLOAT_EQ(gainAtYaw(gain, config, gain.best_yaw_rad), gain.best_gain_m3);
    for (int i = 0; i < 720; ++i) {
      EXPECT_LE(gainAtYaw(gain, config, float(i * kTwoPi / 720)), gain.best_gain_m3 * 1.000001f);
    }
  }
}

/// A 5 x 4 x 2.5 m room (interior from the origin) observed for x < 2.5 only; a few voxels
/// below the weight threshold.
TsdfMap halfObservedRoom() {
  TsdfMap map(mapConfig());
  fillBox(map, {-0.3f, -0.3f, -0.3f}, {5.3f, 4.3f, 2.8f}, [](const Eigen::Vector3f& p) {
    TsdfVoxel voxel;
    if (p.x() >= 2.5f) return voxel;
    const Eigen::Vector3f size(5.0f, 4.0f, 2.5f);
    const float inside = std::min((p.array().min((size - p).array())).minCoeff(), 10.0f);
    voxel.tsdf_m = std::clamp(inside, -0.3f, 0.3f);
    const int hash = int(p.x() * 31 + p.y() * 17 + p.z() * 7) % 13;
    voxel.weight = hash == 0 ? 5e-4f : 1.0f + hash;
    return voxel;
  });
  return map;
}

TEST(ViewGain, HalfObservedRoomLooksAtItsUnobservedHalf) {
  const TsdfMap map = halfObservedRoom();
  ViewGainConfig config;
  config.max_range_m = 5.0f;
  std::vector<Eigen::Vector3f> positions;
  for (float x = 0.5f; x < 2.5f; x += 0.5f) {
    for (float y = 0.6f; y < 4.0f; y += 0.7f) positions.emplace_back(x, y, 1.2f);
  }
  const std::vector<ViewGain> reference = viewGainReference(map, config, positions);
  expectEqualGains(onDevice(map, config, positions), reference);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const ViewGain& gain = reference[i];
    // The unobserved half lies in +x: the best window faces it, the opposite one sees little.
    EXPECT_GT(std::cos(gain.best_yaw_rad), 0.3f) << positions[i].transpose();
    EXPECT_GT(gain.best_gain_m3, 5.0f * gainAtYaw(gain, config, gain.best_yaw_rad + float(M_PI)));
    // Bins facing -x see the observed half up to its wall, then stop: only the few voxels
    // below the weight threshold count.
    const float facing_minus_x = gain.bin_gain_m3[config.yaw_bins / 2];
    EXPECT_LT(facing_minus_x, 0.01f * fanVolume_m3(config, kTwoPi / config.yaw_bins));
  }
  // Nearer the unobserved half, more to gain.
  EXPECT_GT(reference.back().best_gain_m3, reference.front().best_gain_m3);
}

TEST(ViewGain, CoarseStepsAndOtherFansStillAgree) {
  const TsdfMap map = halfObservedRoom();
  ViewGainConfig config;
  config.yaw_bins = 36;
  config.rays_per_bin = 3;
  config.elevation_rays = 5;
  config.step_voxels = 2.5f;
  config.min_range_m = 0.0f;
  config.max_range_m = 3.33f;
  // The far position makes the batch's block box too large for one table: two chunks.
  const std::vector<Eigen::Vector3f> positions = {
      {1.05f, 2.0f, 1.0f}, {-0.95f, -1.0f, 0.5f}, {800.0f, -700.0f, 40.0f}, {2.0f, 1.0f, 1.0f}};
  expectEqualGains(onDevice(map, config, positions), viewGainReference(map, config, positions));
}

TEST(ViewGain, DeviceEqualsReferenceOnAFusedRoom) {
  // A partly mapped room: 8 frames of the simulated room fused with free space, a grid of
  // positions over it (some outside its walls, where rays start in unknown space).
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
  sim::SimSessionConfig session_config;
  session_config.max_frames = 8;
  const sim::SimSessionDataset session(world, 0, session_config);
  MapConfig config = mapConfig();
  config.allocate_free_space = true;
  DeviceFusion fusion(test::sharedContext(), config);
  const TsdfMap map = test::fuseOnDevice(session, config, session.size(), 1, &fusion);
  std::vector<Eigen::Vector3f> positions;
  for (float x = -0.5f; x < 5.6f; x += 0.75f) {
    for (float y = -0.5f; y < 4.6f; y += 0.75f) positions.emplace_back(x, y, 1.3f);
  }
  ViewGainConfig gain_config;
  ViewGainKernel kernel(test::sharedContext(), gain_config);
  const std::vector<ViewGain> device = kernel.run(fusion.map(), positions);
  const std::vector<ViewGain> reference = viewGainReference(map, gain_config, positions);
  expectEqualGains(device, reference);
  // Some positions see much less unknown space than others (the map is partial, not empty).
  float least = 1e9f, most = 0.0f;
  for (const ViewGain& g : reference) {
    least = std::min(least, g.best_gain_m3);
    most = std::max(most, g.best_gain_m3);
  }
  EXPECT_LT(least, 0.5f * most);
}

TEST(ViewGain, WindowsCountBinsInProportion) {
  ViewGainConfig config;
  config.yaw_bins = 12;                         // 30 degree bins
  config.horizontal_fov_rad = float(M_PI / 2);  // windows of 3 bins
  ViewGain gain;
  gain.bin_gain_m3.assign(12, 0.0f);
  gain.bin_gain_m3[3] = 6.0f;   // 90..120 degrees
  gain.bin_gain_m3[0] = 2.0f;   // 0..30
  gain.bin_gain_m3[11] = 4.0f;  // 330..360
  const auto deg = [](double d) { return float(d * M_PI / 180.0); };
  EXPECT_NEAR(gainAtYaw(gain, config, deg(105)), 6.0f, 1e-5);
  EXPECT_NEAR(gainAtYaw(gain, config, deg(150)), 3.0f, 1e-5);  // window 105..195
  EXPECT_NEAR(gainAtYaw(gain, config, deg(166)), 0.0f, 1e-5);
  EXPECT_NEAR(gainAtYaw(gain, config, deg(0)), 6.0f, 1e-5);                 // -45..45 across 0
  EXPECT_NEAR(gainAtYaw(gain, config, deg(-15)), 6.0f, 1e-5);               // -60..30
  EXPECT_NEAR(gainAtYaw(gain, config, deg(30)), 2.0f + 4.0f * 0.5f, 1e-5);  // -15..75
  EXPECT_NEAR(gainAtYaw(gain, config, deg(30 + 720)), gainAtYaw(gain, config, deg(30)), 1e-5);
  config.horizontal_fov_rad = float(kTwoPi);
  EXPECT_NEAR(gainAtYaw(gain, config, deg(77)), 12.0f, 1e-5);
  config.yaw_bins = 13;
  EXPECT_THROW(gainAtYaw(gain, config, 0.0f), InputError);
}

TEST(ViewGain, BadInputIsAnInputError) {
  const auto fails = [](const std::function<void(ViewGainConfig&)>& change) {
    ViewGainConfig config;
    change(config);
    EXPECT_THROW(config.validate(), InputError);
    EXPECT_THROW(viewGainReference(TsdfMap(mapConfig()), config, {{0.0f, 0.0f, 0.0f}}), InputError);
    EXPECT_THROW(ViewGainKernel(test::sharedContext(), config), InputError);
  };
  fails([](ViewGainConfig& c) { c.max_range_m = c.min_range_m; });
  fails([](ViewGainConfig& c) { c.min_range_m = -1.0f; });
  fails([](ViewGainConfig& c) { c.yaw_bins = 0; });
  fails([](ViewGainConfig& c) { c.rays_per_bin = 0; });
  fails([](ViewGainConfig& c) { c.elevation_rays = 0; });
  fails([](ViewGainConfig& c) { c.vertical_fov_rad = 3.5f; });
  fails([](ViewGainConfig& c) { c.horizontal_fov_rad = 0.0f; });
  fails([](ViewGainConfig& c) { c.step_voxels = NAN; });
  fails([](ViewGainConfig& c) { c.min_weight = 0.0f; });
  fails([](ViewGainConfig& c) { c.tsdf_layer = -1; });
  try {
    ViewGainConfig config;
    config.yaw_bins = -3;
    config.validate();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("yaw_bins"), std::string::npos) << e.what();
  }

  const TsdfMap map(mapConfig());
  ViewGainConfig config;
  EXPECT_THROW(viewGainReference(map, config, {{NAN, 0.0f, 0.0f}}), InputError);
  EXPECT_THROW(viewGainReference(map, config, {{1e9f, 0.0f, 0.0f}}), InputError);
  DeviceTsdfMap device(test::sharedContext(), map.config());
  EXPECT_THROW(ViewGainKernel(test::sharedContext(), config).run(device, {{NAN, 0.0f, 0.0f}}),
               InputError);
  config.tsdf_layer = 1;
  EXPECT_THROW(ViewGainKernel(test::sharedContext(), config).run(device, {{0.0f, 0.0f, 0.0f}}),
               InputError);
  config.tsdf_layer = 0;
  EXPECT_TRUE(ViewGainKernel(test::sharedContext(), config).run(device, {}).empty());
}

}  // namespace
}  // namespace strata::explore
