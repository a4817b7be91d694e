// Renders one session of a simulated world along its path and writes it as a TUM RGB-D folder
// with the true poses; prints the frame counts and which movable objects the camera saw.
//   simulate_session [WORLD] [SESSION] [OUT_DIR] [MAX_FRAMES]
// WORLD: a world file or a shipped world's name (default room; found as explore_world finds it);
// SESSION from 0; MAX_FRAMES frames spread over the path (default 30, 0: all at 30 Hz).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <set>
#include <string>

#include "strata/io/tum_writer.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

int main(int argc, char** argv) {
  try {
    const std::string world_path = strata::sim::findWorld(argc > 1 ? argv[1] : "room");
    const int session_index = argc > 2 ? std::atoi(argv[2]) : 0;
    const std::string out = argc > 3 ? argv[3] : "session";
    auto world = std::make_shared<const strata::sim::World>(strata::sim::World::load(world_path));
    strata::sim::SimSessionConfig config;
    config.max_frames = argc > 4 ? std::atoi(argv[4]) : 30;
    const strata::sim::SimSessionDataset session(world, session_index, config);
    strata::TumWriter writer(out, session.intrinsics());
    std::set<int> objects_seen;
    for (std::size_t i = 0; i < session.size(); ++i) {
      strata::sim::SimulatedFrame frame = session.render(i);  // sensor images and their truth
      for (const std::int32_t id : frame.object_ids.ids) {
        if (id > 0) objects_seen.insert(id);  // 0: static structure, -1: nothing hit
      }
      writer.add(strata::sim::makeRgbdFrame(std::move(frame), session.truePoses()[i],
                                            session.timestamp(i), std::to_string(i)));
    }
    writer.finish();
    std::printf(
        "world '%s' session %d of %d: %zu frames of %zu recorded (%dx%d), %zu IMU samples "
        "-> %s\n",
        world->name().c_str(), session_index, world->sessionCount(), session.size(),
        session.recordedFrames(), session.intrinsics().width_px, session.intrinsics().height_px,
        session.imu().size(), out.c_str());
    std::printf("movable objects seen: %zu of %d\n", objects_seen.size(), world->objectCount());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "simulate_session: %s\n", e.what());
    return 1;
  }
  return 0;
}
