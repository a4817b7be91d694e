// Device faults in the middle of a session, through the Mapper: the device runs out of memory
// while the map grows (vk::FaultInjection), or the map's block budget is spent. Either way the
// frame is refused whole with an error naming the cause, every voxel fused before stays exactly as
// it was, the map saves and loads, and fusion goes on once the frame fits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <string>

#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/integrate/block_allocation.h"
#include "strata/mapper/mapper.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/vk/fault_injection.h"

namespace strata {
namespace {

constexpr std::size_t kFirstFrame = 0;  // fused before every fault
constexpr std::size_t kNearFrame = 1;   // sees a little new space
constexpr std::size_t kFarFrame = 40;   // sees a new region: the map must grow

sim::AnalyticDataset smallDataset() {
  sim::AnalyticDatasetConfig config;
  // A quarter of the default resolution, same field of view: the same blocks, 16x fewer pixels.
  config.intrinsics = CameraIntrinsics{160, 120, 131.25f, 131.25f, 79.5f, 59.5f};
  return sim::AnalyticDataset(config);
}

MapperConfig smallConfig() {
  MapperConfig config;
  config.map.voxel_size_m = 0.04f;
  return config;
}

std::vector<BlockIndex> blocksOf(const sim::AnalyticDataset& data, const MapConfig& config,
                                 std::size_t frame) {
  const RgbdFrame f = data.load(frame);
  return allocatedBlocksReference(f.depth, FrameCamera::from(data.intrinsics(), f.T_W_C), config);
}

bool blockLess(const BlockIndex& a, const BlockIndex& b) {
  if (a.z() != b.z()) return a.z() < b.z();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.x() < b.x();
}

/// Blocks `frame` allocates that kFirstFrame did not.
std::size_t newBlocksAfterFirst(const sim::AnalyticDataset& data, const MapConfig& config,
                                std::size_t frame) {
  std::vector<BlockIndex> first = blocksOf(data, config, kFirstFrame);
  std::vector<BlockIndex> later = blocksOf(data, config, frame);
  std::sort(first.begin(), first.end(), blockLess);
  std::sort(later.begin(), later.end(), blockLess);
  std::vector<BlockIndex> added;
  std::set_difference(later.begin(), later.end(), first.begin(), first.end(),
                      std::back_inserter(added), blockLess);
  return added.size();
}

/// The same blocks with the same bytes in every voxel (distance, weight, colour).
void expectSameMap(const TsdfMap& actual, const TsdfMap& expected, const std::string& what) {
  EXPECT_EQ(actual.blockCount(), expected.blockCount()) << what << ": block count";
  std::size_t missing = 0, changed = 0;
  for (const auto& [index, block] : expected.blocks()) {
    const TsdfBlock* other = actual.findBlock(index);
    if (other == nullptr) {
      ++missing;
    } else if (std::memcmp(other->data(), block.data(), sizeof(TsdfBlock)) != 0) {
      ++changed;
    }
  }
  EXPECT_EQ(missing, 0u) << what << ": blocks lost";
  EXPECT_EQ(changed, 0u) << what << ": blocks whose voxels changed";
}

std::string tempMapPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("strata_test_device_faults_" + name + ".strata"))
      .string();
}

/// The map saved at `path` loads into a mapper as `expected`, exactly (and the file is removed).
/// The map at `path`, loaded with `config`, holds `expected` (and, with change detection, its
/// static estimate `expected_static`).
void expectLoads(const std::string& path, const TsdfMap& expected,
                 const MapperConfig& config = smallConfig(),
                 const TsdfMap* expected_static = nullptr) {
  const std::unique_ptr<Mapper> loaded = Mapper::load(path, test::sharedContext(), config);
  expectSameMap(loaded->download(), expected, "loaded map");
  if (expected_static) expectSameMap(loaded->staticMap(), *expected_static, "loaded static map");
  std::filesystem::remove(path);
}

/// The map of kFirstFrame then `frame`, fused with no fault: what a refused frame fused again
/// once it fits must give.
TsdfMap faultFreeMap(const sim::AnalyticDataset& data, std::size_t frame) {
  Mapper mapper(smallConfig(), test::sharedContext());
  mapper.integrate(data.load(kFirstFrame), data.intrinsics());
  mapper.integrate(data.load(frame), data.intrinsics());
  return mapper.download();
}

/// A mapper holding kFirstFrame in a pool of exactly `pool_blocks` that the device cannot grow:
/// the pool's own allocations fail from the start (every other buffer allocates).
std::unique_ptr<Mapper> mapperWithFullPool(const sim::AnalyticDataset& data,
                                           std::uint32_t pool_blocks) {
  MapperConfig config = smallConfig();
  config.map.initial_block_capacity = pool_blocks;
  auto mapper = std::make_unique<Mapper>(config, test::sharedContext());
  vk::FaultInjection::armAllocationFailure({0, vk::FaultInjection::kForever, "TSDF voxel pool"});
  mapper->integrate(data.load(kFirstFrame), data.intrinsics());
  return mapper;
}

/// Integrates `frame`, expecting a DeviceError; returns its message.
std::string refusedFrame(Mapper& mapper, const sim::AnalyticDataset& data, std::size_t frame) {
  try {
    mapper.integrate(data.load(frame), data.intrinsics());
  } catch (const DeviceError& e) {
    return e.what();
  }
  ADD_FAILURE() << "frame " << frame << " should have been refused";
  return "";
}

/// Whether `error` is the injected out-of-memory error (reported, not swallowed or reworded).
bool isOutOfDeviceMemory(const std::string& error) {
  return error.find("VK_ERROR_OUT_OF_DEVICE_MEMORY") != std::string::npos;
}

class DeviceFaults : public ::testing::Test {
 protected:
  void TearDown() override { vk::FaultInjection::disarm(); }
  const sim::AnalyticDataset data_ = smallDataset();
};

TEST_F(DeviceFaults, PoolGrowthOutOfDeviceMemoryRefusesTheFrameAndKeepsTheMap) {
  const std::size_t first_blocks = blocksOf(data_, smallConfig().map, kFirstFrame).size();
  const std::size_t far_new = newBlocksAfterFirst(data_, smallConfig().map, kFarFrame);
  const auto pool_blocks = static_cast<std::uint32_t>(first_blocks + far_new / 2);
  ASSERT_GT(first_blocks + far_new, pool_blocks) << "the far frame must need a bigger pool";

  const std::unique_ptr<Mapper> mapper = mapperWithFullPool(data_, pool_blocks);
  const TsdfMap before = mapper->download();
  const std::string error = refusedFrame(*mapper, data_, kFarFrame);
  EXPECT_TRUE(isOutOfDeviceMemory(error)) << error;
  EXPECT_NE(error.find("TSDF voxel pool"), std::string::npos) << error;
  EXPECT_GT(vk::FaultInjection::failuresInjected(), 0u);

  expectSameMap(mapper->download(), before, "map after the refused frame");
  const std::string path = tempMapPath("pool_growth");
  ASSERT_NO_THROW(mapper->save(path)) << "saving needs no device memory";
  // Memory is back: the saved map loads, and the refused frame fuses as if never tried.
  vk::FaultInjection::disarm();
  expectLoads(path, before);
  ASSERT_NO_THROW(mapper->integrate(data_.load(kFarFrame), data_.intrinsics()));
  expectSameMap(mapper->download(), faultFreeMap(data_, kFarFrame), "map after fusing it again");
}

TEST_F(DeviceFaults, DeviceOutOfMemoryForEveryBufferStillKeepsAndSavesTheMap) {
  const std::size_t first_blocks = blocksOf(data_, smallConfig().map, kFirstFrame).size();
  const std::size_t far_new = newBlocksAfterFirst(data_, smallConfig().map, kFarFrame);
  const std::unique_ptr<Mapper> mapper =
      mapperWithFullPool(data_, static_cast<std::uint32_t>(first_blocks + far_new / 2));
  const TsdfMap before = mapper->download();
  // From now on the device holds nothing more: the failed growth's clean-up must not allocate.
  vk::FaultInjection::armAllocationFailure({0, vk::FaultInjection::kForever, ""});
  const std::string error = refusedFrame(*mapper, data_, kFarFrame);
  EXPECT_TRUE(isOutOfDeviceMemory(error)) << error;

  // Saving copies the map to the host; where that needs no staging buffer it works while full.
  const std::string path = tempMapPath("device_full");
  const bool staged = test::sharedContext().stagedMemory();
  if (!staged) {
    expectSameMap(mapper->download(), before, "map while the device is full");
    ASSERT_NO_THROW(mapper->save(path));
  }
  vk::FaultInjection::disarm();
  expectSameMap(mapper->download(), before, "map after the refused frame");
  if (staged) mapper->save(path);
  expectLoads(path, before);
  ASSERT_NO_THROW(mapper->integrate(data_.load(kFarFrame), data_.intrinsics()));
  expectSameMap(mapper->download(), faultFreeMap(data_, kFarFrame), "map after fusing it again");
}

/// A close-up of the surface kFirstFrame looks at (few blocks), then kFirstFrame: at 1 cm voxels
/// the second frame needs more new blocks than the pool keeps in reserve, so the map grows in the
/// middle of the session.
sim::AnalyticDataset growingSession(const sim::AnalyticDataset& data) {
  const RgbdFrame first = data.load(kFirstFrame);
  const float centre_depth_m = first.depth.at(first.depth.width_px / 2, first.depth.height_px / 2);
  Eigen::Isometry3d close_up = first.T_W_C;
  close_up.translation() += first.T_W_C.linear().col(2) * (centre_depth_m - 0.3);
  sim::AnalyticDatasetConfig config;
  config.intrinsics = data.intrinsics();
  return sim::AnalyticDataset(data.scene(), {close_up, first.T_W_C}, config);
}

TEST_F(DeviceFaults, TheDeviceFillingUpAtAnyAllocationCostsNoFusedFrame) {
  if (test::sharedContext().stagedMemory()) {
    GTEST_SKIP() << "with staged memory, copies to the host need device-side staging buffers";
  }
  const sim::AnalyticDataset session = growingSession(data_);
  MapperConfig config = smallConfig();
  config.map.voxel_size_m = 0.01f;
  // A run without faults gives the map to expect and the number of allocations to sweep.
  vk::FaultInjection::armAllocationFailure({vk::FaultInjection::kForever, 0, ""});
  TsdfMap expected(config.map);
  {
    Mapper mapper(config, test::sharedContext());
    for (std::size_t f = 0; f < session.size(); ++f)
      mapper.integrate(session.load(f), session.intrinsics());
    expected = mapper.download();
  }
  const std::uint64_t allocations = vk::FaultInjection::allocationsSeen();
  ASSERT_GT(allocations, 0u);
  std::size_t refused_with_a_map = 0;  // refusals after at least one frame was fused
  for (std::uint64_t k = 0; k < allocations; ++k) {
    SCOPED_TRACE("the device is full from allocation " + std::to_string(k) + " of " +
                 std::to_string(allocations));
    vk::FaultInjection::armAllocationFailure({k, vk::FaultInjection::kForever, ""});
    std::unique_ptr<Mapper> mapper;
    try {
      mapper = std::make_unique<Mapper>(config, test::sharedContext());
    } catch (const DeviceError& e) {
      EXPECT_TRUE(isOutOfDeviceMemory(e.what())) << e.what();
      continue;  // nothing fused yet, nothing to lose
    }
    for (std::size_t f = 0; f < session.size(); ++f) {
      const TsdfMap before = mapper->download();
      try {
        mapper->integrate(session.load(f), session.intrinsics());
      } catch (const DeviceError& e) {
        EXPECT_TRUE(isOutOfDeviceMemory(e.what())) << e.what();
        refused_with_a_map += before.blockCount() > 0 ? 1 : 0;
        expectSameMap(mapper->download(), before, "map after refused frame " + std::to_string(f));
        vk::FaultInjection::disarm();  // memory is back: the same frame again
        ASSERT_NO_THROW(mapper->integrate(session.load(f), session.intrinsics()));
      }
    }
    expectSameMap(mapper->download(), expected, "map at the end of the session");
  }
  EXPECT_GT(refused_with_a_map, 0u) << "some allocation must fail in the middle of the session";
}

TEST_F(DeviceFaults, WithChangeDetectionEveryLayerIsKeptWhenTheLayersCannotGrow) {
  const sim::AnalyticDataset session = growingSession(data_);  // close-up, then a wide view
  MapperConfig config = smallConfig();
  config.map.voxel_size_m = 0.01f;
  config.change_detection = true;
  config.discover_objects = false;
  config.map.initial_block_capacity = 64;
  Mapper mapper(config, test::sharedContext());
  mapper.integrate(session.load(0), session.intrinsics());
  mapper.beginSession();  // session 1: layers S, 0 and 1, allocated now
  // From now on no layer's pool can grow (TSDF and label pools alike).
  vk::FaultInjection::armAllocationFailure({0, vk::FaultInjection::kForever, "pool"});
  mapper.integrate(session.load(0), session.intrinsics());
  const TsdfMap session_before = mapper.download();
  const TsdfMap static_before = mapper.staticMap();
  const std::string error = refusedFrame(mapper, session, 1);
  EXPECT_TRUE(isOutOfDeviceMemory(error)) << error;
  expectSameMap(mapper.download(), session_before, "session layer after the refused frame");
  expectSameMap(mapper.staticMap(), static_before, "static estimate after the refused frame");
  const std::string path = tempMapPath("change_detection");
  ASSERT_NO_THROW(mapper.save(path));
  vk::FaultInjection::disarm();
  expectLoads(path, session_before, config, &static_before);  // the open session and S
  ASSERT_NO_THROW(mapper.integrate(session.load(1), session.intrinsics()));
  EXPECT_GT(mapper.blockCount(), session_before.blockCount());
  EXPECT_NO_THROW(mapper.endSession());
}

TEST_F(DeviceFaults, FullBlockBudgetRefusesTheFrameWholeAndLeavesRoomForFramesThatFit) {
  MapperConfig config = smallConfig();
  const std::size_t first_blocks = blocksOf(data_, config.map, kFirstFrame).size();
  const std::size_t near_new = newBlocksAfterFirst(data_, config.map, kNearFrame);
  const std::size_t far_new = newBlocksAfterFirst(data_, config.map, kFarFrame);
  // Room for the near frame's new blocks, not for the far frame's.
  config.map.max_block_capacity = static_cast<std::uint32_t>(first_blocks + near_new + 4);
  ASSERT_GT(far_new, near_new + 4) << "the far frame must exceed the budget";
  Mapper mapper(config, test::sharedContext());
  mapper.integrate(data_.load(kFirstFrame), data_.intrinsics());
  const TsdfMap before = mapper.download();

  const std::string error = refusedFrame(mapper, data_, kFarFrame);
  EXPECT_NE(error.find("max_block_capacity"), std::string::npos) << error;
  EXPECT_NE(error.find(std::to_string(config.map.max_block_capacity)), std::string::npos) << error;
  expectSameMap(mapper.download(), before, "map after the refused frame");
  EXPECT_EQ(mapper.blockCount(), before.blockCount()) << "the refused frame holds no block";
  const std::string path = tempMapPath("budget");
  mapper.save(path);
  expectLoads(path, before);
  // The budget the refused frame did not use is still there for a frame that fits.
  ASSERT_NO_THROW(mapper.integrate(data_.load(kNearFrame), data_.intrinsics()));
  expectSameMap(mapper.download(), faultFreeMap(data_, kNearFrame), "map after a frame that fits");
}

}  // namespace
}  // namespace strata
