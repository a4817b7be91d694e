#pragma once
// Shared by the LCM tests: a strata-mapper running in-process on LCM's memq:// provider (nothing
// touches the network), a collector of what it publishes, small synthetic sessions.
#include <atomic>
#include <chrono>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "mapper_node/mapper_core.h"
#include "mapper_node/mapper_node.h"
#include "player/play_publisher.h"
#include "strata/sim/session/sim_session.h"
#include "strata/change_event_t.hpp"
#include "strata/keyframe_score_t.hpp"
#include "strata/map_stats_t.hpp"
#include "strata/mesh_update_t.hpp"
#include "strata/object_update_t.hpp"

namespace strata::test {

/// Latest mesh per block over `updates` (what a viewer shows), as one mesh's triangle count.
std::size_t viewerTriangles(const std::vector<mesh_update_t>& updates);

/// Everything the mapper publishes, kept for assertions. Handlers run on the mapper's receive
/// thread (memq delivers through the one LCM object), so access goes through the mutex.
struct MapperOutputs {
  std::mutex mutex;
  std::vector<mesh_update_t> mesh_updates;
  std::vector<map_stats_t> stats;
  std::vector<change_event_t> change_events;
  std::vector<object_update_t> object_updates;
  std::vector<keyframe_score_t> keyframe_scores;
  int esdf_slices = 0;

  map_stats_t latestStats();
  /// Latest mesh per block over all updates (a viewer's state), as one mesh's triangle count.
  std::size_t viewerTriangles();
};

/// A mapper on memq://, fusing on the test's shared Vulkan context, running on a thread.
class InProcessMapper {
 public:
  explicit InProcessMapper(const apps::MapperOptions& options);
  ~InProcessMapper();  // stops it

  lcm::LCM& lcm() { return lcm_; }
  apps::MapperCore& core() { return *core_; }
  apps::MapperNode& node() { return *node_; }
  MapperOutputs& outputs() { return outputs_; }
  /// Stops the node (it fuses what is queued and saves to --map when set); returns run()'s value.
  bool stop();
  /// Polls `ready` until it holds or `timeout_s` passes.
  static bool waitFor(const std::function<bool()>& ready, double timeout_s = 60.0);

 private:
  void subscribeOutputs(const apps::MapperOptions& options);

  lcm::LCM lcm_;
  MapperOutputs outputs_;
  std::unique_ptr<apps::MapperCore> core_;
  std::unique_ptr<apps::MapperNode> node_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  bool stopped_ = false;
  bool saved_ = true;
};

/// Mapper options for tests: 5 cm voxels, no change detection unless asked, no map file.
apps::MapperOptions testMapperOptions();

/// Session `session` of the shipped room, `frames` frames along its path (noise on).
std::unique_ptr<sim::SimSessionDataset> roomSession(int session, int frames);

}  // namespace strata::test
