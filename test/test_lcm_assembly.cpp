// The plain C++ behind strata-mapper's handlers: pose interpolation, frame assembly (pose lookup,
// order, sizes), the drop-oldest queue, per-block meshes, ESDF slices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "strata/core/error.h"
#include "strata/esdf/esdf.h"
#include "strata/integrate/tsdf_integration.h"
#include "strata/lcm/block_mesh_msg.h"
#include "strata/lcm/esdf_slice_msg.h"
#include "strata/lcm/frame_assembler.h"
#include "strata/lcm/frame_queue.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/sim/analytic_dataset.h"

namespace strata::lcm_io {
namespace {

Eigen::Isometry3d poseAt(double x_m, double yaw_rad) {
  return Eigen::Translation3d(x_m, 0.0, 1.0) * Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ());
}

ReceivedFrame smallFrame(std::int64_t utime, bool with_pose) {
  ReceivedFrame r;
  r.utime = utime;
  r.camera_id = "depth";
  r.frame.depth = DepthImage(4, 3, 1.0f);
  r.has_pose = with_pose;
  return r;
}

CameraIntrinsics smallCamera() {
  CameraIntrinsics k;
  k.width_px = 4;
  k.height_px = 3;
  k.cx_px = 1.5f;
  k.cy_px = 1.0f;
  return k;
}

TEST(LcmPoseBuffer, InterpolatesPositionLinearlyAndOrientationBySlerp) {
  PoseBuffer poses(16, 1000000);
  poses.add(1000, poseAt(0.0, 0.0));
  poses.add(2000, poseAt(1.0, 1.0));
  Eigen::Isometry3d T;
  ASSERT_EQ(poses.lookup(1250, &T), PoseLookup::kFound);
  EXPECT_NEAR(T.translation().x(), 0.25, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(T.rotation()).angle(), 0.25, 1e-12);
  ASSERT_EQ(poses.lookup(2000, &T), PoseLookup::kFound);
  EXPECT_NEAR(T.translation().x(), 1.0, 1e-12);
  EXPECT_EQ(poses.lookup(2001, &T), PoseLookup::kNotYet);
  EXPECT_EQ(poses.lookup(999, &T), PoseLookup::kTooOld);
  EXPECT_THROW(poses.add(2000, poseAt(0, 0)), InputError);  // out of order
  poses.add(5000000, poseAt(2.0, 0.0));
  EXPECT_EQ(poses.lookup(3000, &T), PoseLookup::kGapTooLarge);
}

TEST(LcmFrameAssembler, FramesWaitForTheirPoseAndBadOnesAreRejected) {
  FrameAssembler assembler;
  EXPECT_THROW(assembler.onFrame(smallFrame(100, true)), InputError);  // no camera_info yet
  assembler.onCameraInfo("depth", smallCamera());
  EXPECT_TRUE(assembler.onPose(50, poseAt(0.0, 0.0)).ready.empty());
  EXPECT_TRUE(assembler.onFrame(smallFrame(100, false)).ready.empty());  // waits for a pose
  EXPECT_EQ(assembler.pendingFrames(), 1u);
  const AssemblerOutput out = assembler.onPose(150, poseAt(1.0, 0.0));
  ASSERT_EQ(out.ready.size(), 1u);
  EXPECT_NEAR(out.ready[0].frame.T_W_C.translation().x(), 0.5, 1e-12);
  EXPECT_THROW(assembler.onFrame(smallFrame(100, true)), InputError);  // stamp not after 100
  ReceivedFrame wrong_size = smallFrame(200, true);
  wrong_size.frame.depth = DepthImage(5, 3, 1.0f);
  EXPECT_THROW(assembler.onFrame(wrong_size), InputError);
  EXPECT_EQ(assembler.onFrame(smallFrame(300, true)).ready.size(), 1u);
}

TEST(LcmFrameAssembler, FramesOlderThanEveryPoseOrBeyondThePendingLimitAreDropped) {
  AssemblerConfig config;
  config.max_pending_frames = 2;
  FrameAssembler assembler(config);
  assembler.onCameraInfo("depth", smallCamera());
  assembler.onPose(1000, poseAt(0.0, 0.0));
  AssemblerOutput old = assembler.onFrame(smallFrame(500, false));
  EXPECT_EQ(old.dropped_no_pose, 1u);
  std::size_t dropped = 0;
  for (std::int64_t t = 2000; t <= 5000; t += 1000) {
    dropped += assembler.onFrame(smallFrame(t, false)).dropped_no_pose;
  }
  EXPECT_EQ(dropped, 2u);  // 2000 and 3000 made room for 4000 and 5000
  const AssemblerOutput out = assembler.onPose(6000, poseAt(1.0, 0.0));
  ASSERT_EQ(out.ready.size(), 2u);
  EXPECT_EQ(out.ready[0].utime, 4000);
  EXPECT_EQ(out.ready[1].utime, 5000);
}

TEST(LcmFrameQueue, DropsTheOldestWhenFull) {
  DropOldestQueue<int> queue(3);
  std::size_t dropped = 0;
  for (int i = 1; i <= 5; ++i) dropped += queue.push(i);
  EXPECT_EQ(dropped, 2u);
  EXPECT_EQ(queue.size(), 3u);
  for (int expected = 3; expected <= 5; ++expected) {
    EXPECT_EQ(queue.pop(std::chrono::milliseconds(0)).value(), expected);
  }
  EXPECT_FALSE(queue.pop(std::chrono::milliseconds(1)).has_value());
}

TsdfMap smallFusedMap() {
  MapConfig config;
  config.voxel_size_m = 0.05f;
  TsdfMap map(config);
  sim::AnalyticDataset dataset;
  for (std::size_t i = 0; i < 3; ++i) {
    integrateFrameReference(map, dataset.load(i * 10), dataset.intrinsics());
  }
  return map;
}

using Triangle = std::array<float, 9>;

std::vector<Triangle> sortedTriangles(const Mesh& mesh) {
  std::vector<Triangle> out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 3; ++a) tri[3 * k + a] = mesh.vertices[t[k]][a];
    }
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(LcmBlockMesh, BlockMeshesTogetherAreTheWholeMapsMesh) {
  const TsdfMap map = smallFusedMap();
  const Mesh whole = extractMesh(map);
  ASSERT_GT(whole.triangles.size(), 100u);
  Mesh joined;
  for (const mesh_block_t& block : meshBlockMessages(map, map.sortedBlockIndices())) {
    const Mesh part = toMesh(block);
    const int offset = static_cast<int>(joined.vertices.size());
    joined.vertices.insert(joined.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const Eigen::Vector3i& t : part.triangles) {
      joined.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
    }
  }
  EXPECT_EQ(sortedTriangles(joined), sortedTriangles(whole));
}

TEST(LcmBlockMesh, ChangedBlocksRemeshTheirNeighboursToo) {
  const TsdfMap map = smallFusedMap();
  const BlockIndex changed = map.sortedBlockIndices()[map.blockCount() / 2];
  const std::vector<BlockIndex> blocks = blocksToRemesh(map, {changed});
  EXPECT_GT(blocks.size(), 1u);
  EXPECT_LE(blocks.size(), 27u);
  for (const BlockIndex& b : blocks) {
    EXPECT_LE((b - changed).cwiseAbs().maxCoeff(), 1);
    EXPECT_NE(map.findBlock(b), nullptr);
  }
  EXPECT_TRUE(std::find(blocks.begin(), blocks.end(), changed) != blocks.end());
}

TEST(LcmEsdfSlice, CellsCarryTheVoxelDistancesAtTheSliceHeight) {
  const TsdfMap map = smallFusedMap();
  EsdfMap esdf = computeEsdfReference(map, EsdfConfig{});
  esdf.voxel_size_m = map.config().voxel_size_m;
  const float z_m = 0.52f;
  const esdf_slice_t slice = makeEsdfSlice(esdf, z_m, 1);
  ASSERT_GT(slice.width, 0);
  ASSERT_GT(slice.height, 0);
  EXPECT_NEAR(slice.z_m, 0.525f, 1e-6f);  // centre of voxel layer 10
  std::size_t observed = 0;
  for (int row = 0; row < slice.height; ++row) {
    for (int col = 0; col < slice.width; ++col) {
      const float x = slice.origin_x_m + col * slice.resolution_m;
      const float y = slice.origin_y_m + row * slice.resolution_m;
      const GlobalVoxelIndex v(static_cast<int>(std::floor(x / 0.05f)),
                               static_cast<int>(std::floor(y / 0.05f)), 10);
      const EsdfVoxel* voxel = esdf.findVoxel(v);
      if (slice.state[row][col] == kSliceObserved) {
        ++observed;
        ASSERT_NE(voxel, nullptr);
        EXPECT_EQ(slice.distance_m[row][col], voxel->distance_m);
      } else {
        EXPECT_TRUE(std::isnan(slice.distance_m[row][col]));
      }
    }
  }
  EXPECT_GT(observed, 50u);
}

}  // namespace
}  // namespace strata::lcm_io
