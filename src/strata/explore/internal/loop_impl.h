#pragma once
// The exploration loop's state (exploration_loop.cpp, exploration_setup.cpp).
#include <memory>

#include "strata/explore/exploration_loop.h"
#include "strata/explore/surface_hits.h"
#include "strata/plan/collision_checker.h"
#include "strata/sim/sensors/rgbd_camera.h"

namespace strata::explore {

sim::RgbdCameraConfig cameraConfig(const ExplorationConfig& config);
MapperConfig mapperConfig(const ExplorationConfig& config);
SurfaceHitsConfig surfaceHitsConfig(const ExplorationConfig& config);

struct ExplorationLoop::Impl {
  Impl(const ExplorationConfig& config, const sim::World& world, const RobotPose& start,
       vk::Context& context)
      : camera(cameraConfig(config)),
        follower(config.robot, start),
        gain(context, config.gain),
        hits(surfaceHitsConfig(config)) {
    const sim::Light& light = world.session(0).light;
    lighting.direction_W = light.direction_W.normalized();
    lighting.intensity = light.intensity;
    lighting.ambient = light.ambient;
  }

  sim::RgbdCamera camera;
  sim::Lighting lighting;
  PathFollower follower;
  ViewGainKernel gain;
  std::unique_ptr<plan::DeviceCollisionChecker> checker;  // after the first ESDF update
  SurfaceHits hits;
  std::unique_ptr<HitGuardedChecker> guarded;  // checker AND hits, with config.surface_hits
};

}  // namespace strata::explore
