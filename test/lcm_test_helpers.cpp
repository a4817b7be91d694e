#include "lcm_test_helpers.h"

#include <unordered_map>

#include "fusion_fixture.h"
#include "strata/lcm/block_mesh_msg.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"
#include "strata/esdf_slice_t.hpp"

namespace strata::test {
namespace {

// LCM 1.3's C++ API takes plain functions with a context pointer (no lambdas).
void keepMesh(const lcm::ReceiveBuffer*, const std::string&, const mesh_update_t* m,
              MapperOutputs* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  out->mesh_updates.push_back(*m);
}
void keepStats(const lcm::ReceiveBuffer*, const std::string&, const map_stats_t* m,
               MapperOutputs* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  out->stats.push_back(*m);
}
void keepChange(const lcm::ReceiveBuffer*, const std::string&, const change_event_t* m,
                MapperOutputs* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  out->change_events.push_back(*m);
}
void keepObjects(const lcm::ReceiveBuffer*, const std::string&, const object_update_t* m,
                 MapperOutputs* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  out->object_updates.push_back(*m);
}
void keepScore(const lcm::ReceiveBuffer*, const std::string&, const keyframe_score_t* m,
               MapperOutputs* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  out->keyframe_scores.push_back(*m);
}
void countEsdf(const lcm::ReceiveBuffer*, const std::string&, const esdf_slice_t*,
               MapperOutputs* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  ++out->esdf_slices;
}

}  // namespace

map_stats_t MapperOutputs::latestStats() {
  std::lock_guard<std::mutex> lock(mutex);
  return stats.empty() ? map_stats_t{} : stats.back();
}

std::size_t viewerTriangles(const std::vector<mesh_update_t>& updates) {
  std::unordered_map<BlockIndex, std::size_t, BlockIndexHash> triangles;
  for (const mesh_update_t& update : updates) {
    if (update.full) triangles.clear();
    for (const mesh_block_t& block : update.blocks) {
      triangles[BlockIndex(block.index[0], block.index[1], block.index[2])] =
          static_cast<std::size_t>(block.num_triangles);
    }
  }
  std::size_t total = 0;
  for (const auto& [block, count] : triangles) total += count;
  return total;
}

std::size_t MapperOutputs::viewerTriangles() {
  std::lock_guard<std::mutex> lock(mutex);
  return test::viewerTriangles(mesh_updates);
}

InProcessMapper::InProcessMapper(const apps::MapperOptions& options) : lcm_("memq://") {
  subscribeOutputs(options);
  core_ = std::make_unique<apps::MapperCore>(sharedContext(), options);
  node_ = std::make_unique<apps::MapperNode>(lcm_, lcm_, *core_, options);
  thread_ = std::thread([this] { saved_ = node_->run(stop_); });
}

InProcessMapper::~InProcessMapper() { stop(); }

bool InProcessMapper::stop() {
  if (!stopped_) {
    stop_ = true;
    thread_.join();
    stopped_ = true;
  }
  return saved_;
}

bool InProcessMapper::waitFor(const std::function<bool()>& ready, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!ready()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

void InProcessMapper::subscribeOutputs(const apps::MapperOptions& options) {
  lcm_.subscribeFunction(options.channels.mesh, &keepMesh, &outputs_);
  lcm_.subscribeFunction(options.channels.stats, &keepStats, &outputs_);
  lcm_.subscribeFunction(options.channels.change, &keepChange, &outputs_);
  lcm_.subscribeFunction(options.channels.objects, &keepObjects, &outputs_);
  lcm_.subscribeFunction(options.channels.esdf, &countEsdf, &outputs_);
  lcm_.subscribeFunction(options.channels.keyframe, &keepScore, &outputs_);
}

apps::MapperOptions testMapperOptions() {
  apps::MapperOptions options;
  options.url = "memq://";
  options.map_path.clear();
  options.change_detection = false;
  options.esdf_rate_hz = 0.0;
  options.mesh_rate_hz = 0.0;  // after every frame
  options.queue_capacity = 64;
  options.quiet = true;
  return options;
}

std::unique_ptr<sim::SimSessionDataset> roomSession(int session, int frames) {
  static const auto world =
      std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
  sim::SimSessionConfig config;
  config.max_frames = frames;
  return std::make_unique<sim::SimSessionDataset>(world, session, config);
}

}  // namespace strata::test
