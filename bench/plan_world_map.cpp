#include "plan_world_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "strata/esdf/esdf.h"
#include "strata/core/parallel_for.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

TsdfBlock truthBlock(const sim::WorldScene& scene, const BlockIndex& b, float voxel_m,
                     float trunc_m) {
  TsdfBlock block;
  for (int i = 0; i < kVoxelsPerBlock; ++i) {
    const Eigen::Vector3i local(i % kBlockEdge, i / kBlockEdge % kBlockEdge,
                                i / (kBlockEdge * kBlockEdge));
    const float d = scene.signedDistance(voxelCenter(b * kBlockEdge + local, voxel_m));
    block[i].tsdf_m = std::clamp(d, -trunc_m, trunc_m);
    block[i].weight = d > -trunc_m ? 20.0f : 0.0f;
    block[i].color_rgba = packRgb(128, 128, 128);
  }
  return block;
}

}  // namespace

WorldMap buildWorldMap(const std::string& world_name, float voxel_size_m,
                       float esdf_max_distance_m) {
  const sim::World world = sim::World::load(sim::findWorld(world_name));
  const std::unique_ptr<sim::WorldScene> scene = world.buildScene(0);
  MapConfig config;
  config.voxel_size_m = voxel_size_m;
  WorldMap out;
  out.tsdf = TsdfMap(config);
  const auto start = Clock::now();
  const Eigen::AlignedBox3d bounds = world.bounds();
  const float block_m = config.blockSize();
  const BlockIndex b0 = (bounds.min().cast<float>() / block_m).array().floor().cast<int>();
  const BlockIndex b1 = (bounds.max().cast<float>() / block_m).array().floor().cast<int>();
  std::vector<BlockIndex> indices;
  for (int z = b0.z(); z <= b1.z(); ++z)
    for (int y = b0.y(); y <= b1.y(); ++y)
      for (int x = b0.x(); x <= b1.x(); ++x) indices.emplace_back(x, y, z);
  std::vector<TsdfBlock> blocks(indices.size());
  const float trunc_m = config.truncationDistance();
  parallelForChunks(indices.size(), resolveThreadCount(0), 4,
                            [&](std::size_t begin, std::size_t end) {
                              for (std::size_t i = begin; i < end; ++i) {
                                blocks[i] = truthBlock(*scene, indices[i], voxel_size_m, trunc_m);
                              }
                            });
  for (std::size_t i = 0; i < indices.size(); ++i) out.tsdf.allocateBlock(indices[i]) = blocks[i];
  out.tsdf_ms = msSince(start);
  EsdfConfig esdf_config;
  esdf_config.max_distance_m = esdf_max_distance_m;
  esdf_config.validate(voxel_size_m);
  const auto esdf_start = Clock::now();
  out.esdf = computeEsdfReference(out.tsdf, esdf_config);
  out.esdf_ms = msSince(esdf_start);
  return out;
}

}  // namespace strata::bench
