// Layers of the device map (step 1): session layers share the block index, layer 0 stays
// the default for fusion and the ESDF, layers by device address compute what bindings compute.
#include <gtest/gtest.h>

#include <cmath>

#include "change_pipeline_helpers.h"
#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/change/change_device.h"
#include "strata/integrate/device_fusion.h"
#include "strata/esdf/esdf.h"
#include "map_compare.h"

namespace strata {
namespace {

using change::LabelMap;
using change::VoxelLabel;

TEST(ChangeLayers, SessionLayersShareBlocksAndLayerZeroStaysDefault) {
  const sim::AnalyticDataset data = test::analyticSession({}, 4);
  const MapConfig config = test::testMapConfig(0.05f, false);
  const TsdfMap plain = test::fuseOnDevice(data, config, 4);
  MapConfig small = config;
  small.initial_block_capacity = 64;  // the pool and every layer grow several times
  DeviceFusion fusion(test::sharedContext(), small);
  EXPECT_EQ(fusion.map().addTsdfLayer(), 1);
  EXPECT_EQ(fusion.map().addLabelLayer(), 0);
  for (std::size_t i = 0; i < 4; ++i) fusion.integrate(data.load(i), data.intrinsics(), 1);
  EXPECT_GT(fusion.map().blockCount(), 64u);
  TsdfMap layer0(config), layer1(config);
  fusion.map().download(layer0, 0);
  fusion.map().download(layer1, 1);
  const test::MapDifference d = test::compareMaps(layer1, plain, 1e-6f, 1e-6f);
  EXPECT_EQ(d.distance_mismatches + d.weight_mismatches + d.blocks_only_in_a + d.blocks_only_in_b,
            0u);
  EXPECT_EQ(layer0.blockCount(), layer1.blockCount()) << "blocks are shared";
  test::forEachVoxel(layer0, [](const GlobalVoxelIndex&, const TsdfVoxel& v) {
    ASSERT_EQ(v.weight, 0.0f) << "layer 0 was never fused";
  });
  EXPECT_EQ(change::downloadLabels(fusion.map(), 0).count(VoxelLabel::kUnknown),
            layer1.blockCount() * kVoxelsPerBlock);
  // A layer upload keeps the other layers; the default layer still fuses as before.
  fusion.map().uploadLayer(plain, 0);
  fusion.integrate(data.load(0), data.intrinsics());
  fusion.map().download(layer1, 1);
  EXPECT_EQ(test::compareMaps(layer1, plain, 1e-6f, 1e-6f).distance_mismatches, 0u);
  EXPECT_THROW(fusion.integrate(data.load(0), data.intrinsics(), 2), InputError);
  // A layer upload that needs more blocks than the pool holds grows every layer first.
  DeviceTsdfMap grown(test::sharedContext(), small);
  grown.addTsdfLayer();
  grown.uploadLayer(plain, 1);
  TsdfMap uploaded(config);
  grown.download(uploaded, 1);
  EXPECT_EQ(test::compareMaps(uploaded, plain, 0.0f, 0.0f).distance_mismatches, 0u);
  EXPECT_EQ(grown.blockCount(), plain.blockCount());
  // The ESDF follows the same slots and reads layer 0.
  DeviceEsdf esdf(test::sharedContext(), fusion.map());
  esdf.updateAll();
  EsdfMap device;
  esdf.download(device);
  fusion.map().download(layer0, 0);
  const EsdfMap reference = computeEsdfReference(layer0, esdf.config());
  std::size_t compared = 0, off = 0;
  for (const auto& [index, block] : reference.blocks) {
    const auto it = device.blocks.find(index);
    ASSERT_NE(it, device.blocks.end());
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      ++compared;
      off += std::fabs(block[i].distance_m - it->second[i].distance_m) > 0.05f ? 1 : 0;
    }
  }
  EXPECT_GT(compared, 0u);
  EXPECT_EQ(off, 0u) << "ESDF of layer 0 on a map with more layers";
}

/// Two sessions through DeviceChange directly on one map; `binding_limit` 0 forces every layer to
/// be reached by device address.
struct DirectRun {
  TsdfMap s;
  LabelMap d, p1;
};
DirectRun runDirect(const sim::AnalyticDataset& a, const sim::AnalyticDataset& b,
                    std::uint64_t binding_limit) {
  const MapConfig config = test::testMapConfig(0.05f, false);
  DeviceFusion fusion(test::sharedContext(), config);
  DeviceTsdfMap& map = fusion.map();
  for (int i = 0; i < 2; ++i) map.addTsdfLayer();   // sessions 0, 1: layers 1, 2
  for (int i = 0; i < 4; ++i) map.addLabelLayer();  // D, raw, P0, P1
  change::DeviceChange change(test::sharedContext(), map, test::testChangeConfig(0.05f));
  change.setBindingLimit(binding_limit);
  for (int s = 0; s < 2; ++s) {
    const sim::AnalyticDataset& data = s == 0 ? a : b;
    for (std::size_t i = 0; i < data.size(); ++i) {
      fusion.integrate(data.load(i), data.intrinsics(), s + 1);
    }
    change::ChangeLayers layers;
    layers.session_tsdf = s + 1;
    layers.session_parts = {{s + 1, s + 2}};
    change.update(layers);
  }
  DirectRun run{TsdfMap(config), change::downloadLabels(map, 0), change::downloadLabels(map, 3)};
  map.download(run.s, 0);
  return run;
}

TEST(ChangeLayers, LayersByDeviceAddressGiveTheSameResult) {
  sim::Box box;
  box.centre_W = Eigen::Vector3d(-1.0, -0.3, 0.15);
  box.half_extents_m = Eigen::Vector3d(0.15, 0.15, 0.15);
  const sim::AnalyticDataset a = test::analyticSession({}, 6);
  const sim::AnalyticDataset b = test::analyticSession({box}, 6);
  const DirectRun bound = runDirect(a, b, ~std::uint64_t{0});
  const DirectRun addressed = runDirect(a, b, 0);
  EXPECT_GT(bound.p1.count(VoxelLabel::kDynamic), 50u) << "the box that appeared";
  EXPECT_EQ(change::labelAgreement(bound.d, addressed.d), 1.0);
  EXPECT_EQ(change::labelAgreement(bound.p1, addressed.p1), 1.0);
  EXPECT_EQ(test::compareValues(addressed.s, bound.s, 0.0f, 1e-6f).over_tolerance, 0u);
}

}  // namespace
}  // namespace strata
