// Explores a simulated world: a MAV with an RGB-D camera flies where the history-aware planner
// sends it while a Mapper fuses what it sees; prints the share of the reachable free space
// observed as it grows.   explore_world [WORLD] [SIM_SECONDS]
// WORLD: a world file or a shipped world's name (room, office, warehouse, deadend; default room),
// looked up in $STRATA_WORLDS_DIR, else the worlds/ folder of the source tree Strata was built from.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "strata/explore/exploration_loop.h"
#include "strata/explore/history_planner.h"
#include "strata/sim/world/world_paths.h"

namespace ex = strata::explore;

int main(int argc, char** argv) {
  try {
    const std::string world_path = strata::sim::findWorld(argc > 1 ? argv[1] : "room");
    const strata::sim::World world = strata::sim::World::load(world_path);
    ex::ExplorationConfig config;
    config.time_limit_s = argc > 2 ? std::strtod(argv[2], nullptr) : 60.0;  // simulated seconds
    config.voxel_size_m = ex::defaultVoxelSize(world);  // 5 cm for small worlds, else 10 cm
    config.validate();
    // Start near the first room's centre at 1.2 m; the truth is the free space reachable from it.
    const Eigen::Vector3f start = ex::defaultStart(world, 1.2f, config);
    const Eigen::AlignedBox3f bounds(world.bounds().min().cast<float>(),
                                     world.bounds().max().cast<float>());
    const ex::ExplorationTruth truth(world, bounds, start, config.voxel_size_m);
    const auto context = strata::vk::Context::create();
    ex::ExplorationLoop loop(world, truth, config, ex::RobotPose{start, 0.0f}, *context);
    ex::HistoryPlanner planner(ex::HistoryConfig{});
    const ex::ExplorationResult result =
        loop.run(planner, [](const ex::CurvePoint& p, const ex::StepRecord*) {
          std::printf("t = %5.1f s: explored %5.1f %%, flown %5.1f m\n", p.sim_time_s,
                      100.0 * p.explored_fraction, p.path_length_m);
        });
    std::printf(
        "%s: explored %.1f %% of %zu reachable voxels in %.0f s simulated (stop: %s), "
        "path %.1f m, %d collisions, %.1f s wall on %s\n",
        world.name().c_str(), 100.0 * result.explored_fraction, result.reachable_voxels,
        result.sim_time_s, result.stop_reason.c_str(), result.path_length_m, result.collisions(),
        result.wall_s, context->deviceName().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "explore_world: %s\n", e.what());
    return 1;
  }
  return 0;
}
