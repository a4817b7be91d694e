// Builds a map of a wall from synthetic depth frames, updates its ESDF and queries the distance
// and collision along a straight path towards the wall.   esdf_path
#include <cstdio>
#include <exception>

#include "strata/mapper/mapper.h"
#include "strata/vk/vk.h"

namespace {

// A 160x120 camera looking down +z at a flat wall 2 m away (world z = 2).
strata::RgbdFrame wallFrame(const strata::CameraIntrinsics& camera, double x_m) {
  strata::RgbdFrame frame;
  frame.depth = strata::DepthImage(camera.width_px, camera.height_px, 2.0f);
  frame.T_W_C = Eigen::Isometry3d::Identity();
  frame.T_W_C.translation() = Eigen::Vector3d(x_m, 0.0, 0.0);
  return frame;
}

}  // namespace

int main() {
  try {
    const auto context = strata::vk::Context::create();
    strata::CameraIntrinsics camera;
    camera.width_px = 160;
    camera.height_px = 120;
    camera.fx_px = camera.fy_px = 120.0f;
    camera.cx_px = 79.5f;
    camera.cy_px = 59.5f;
    strata::MapperConfig config;
    config.map.voxel_size_m = 0.05f;
    config.map.allocate_free_space = true;  // the ESDF then covers the space before the wall
    config.esdf = true;
    strata::Mapper mapper(config, *context);
    for (int i = 0; i < 5; ++i) mapper.integrate(wallFrame(camera, 0.1 * i), camera);
    mapper.updateEsdf();
    std::printf("distance to the wall along the optical axis (truth: 2 - z):\n");
    for (float z = 0.5f; z <= 1.91f; z += 0.2f) {
      const strata::EsdfSample s = mapper.distance(Eigen::Vector3f(0.2f, 0.0f, z));
      std::printf("  z = %.1f m: %.3f m%s\n", z, s.distance_m,
                  s.status == strata::EsdfStatus::kKnown ? "" : " (unknown)");
    }
    // Unknown space counts as occupied: the robot's sphere must stay inside the observed frustum.
    const bool short_free = mapper.isPathFree({{0.2f, 0.0f, 1.0f}, {0.2f, 0.0f, 1.4f}}, 0.2f);
    const bool long_free = mapper.isPathFree({{0.2f, 0.0f, 1.0f}, {0.2f, 0.0f, 1.95f}}, 0.2f);
    std::printf("a 0.2 m robot from z 1.0 to 1.4: %s; to 1.95: %s\n",
                short_free ? "free" : "blocked", long_free ? "free" : "blocked");
    return short_free && !long_free ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "esdf_path: %s\n", e.what());
    return 1;
  }
}
