#include "player/play_source.h"

#include "strata/sim/sim_setup.h"
#include "strata/core/error.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::apps {
namespace {

constexpr const char* kSimPrefix = "sim:";

PlaySource openSim(const std::string& spec, int sim_frames, bool sim_noise, bool with_imu) {
  std::string world_name = spec.substr(std::string(kSimPrefix).size());
  int session = 0;
  const std::size_t colon = world_name.rfind(':');
  if (colon != std::string::npos) {
    const std::string index = world_name.substr(colon + 1);
    try {
      std::size_t used = 0;
      session = std::stoi(index, &used);
      if (used != index.size()) throw std::invalid_argument(index);
    } catch (const std::exception&) {
      throw InputError("'" + spec + "': session '" + index + "' is not a number");
    }
    world_name = world_name.substr(0, colon);
  }
  if (world_name.empty()) world_name = "room";
  const auto world = sim::loadWorld(sim::findWorld(world_name), 0, 0);
  if (session < 0 || session >= world->sessionCount()) {
    throw InputError("'" + spec + "': world has sessions 0.." +
                     std::to_string(world->sessionCount() - 1));
  }
  auto dataset = std::make_unique<sim::SimSessionDataset>(
      world, session, sim::sessionConfig(30.0, sim_frames, sim_noise, false));
  PlaySource source;
  if (with_imu) source.imu = dataset->imu();
  source.dataset = std::move(dataset);
  return source;
}

}  // namespace

PlaySource openPlaySource(const std::string& spec, int sim_frames, bool sim_noise, bool with_imu) {
  if (spec.rfind(kSimPrefix, 0) == 0) return openSim(spec, sim_frames, sim_noise, with_imu);
  if (with_imu) throw InputError("--imu needs a synthetic session (sim:WORLD[:SESSION])");
  PlaySource source;
  source.dataset = openDataset(spec);
  return source;
}

}  // namespace strata::apps
