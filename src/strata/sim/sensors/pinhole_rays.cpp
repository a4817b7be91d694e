#include "strata/sim/sensors/pinhole_rays.h"

#include "strata/core/parallel_for.h"

namespace strata::sim {

PixelRayTable makePixelRayTable(const CameraIntrinsics& intrinsics) {
  intrinsics.validate();
  PixelRayTable table;
  table.width_px = intrinsics.width_px;
  table.height_px = intrinsics.height_px;
  const std::size_t count = static_cast<std::size_t>(table.width_px) * table.height_px;
  table.directions_C.resize(count);
  table.z_per_t.resize(count);
  const double fx = intrinsics.fx_px, fy = intrinsics.fy_px;
  const double cx = intrinsics.cx_px, cy = intrinsics.cy_px;
  for (int v = 0; v < table.height_px; ++v) {
    for (int u = 0; u < table.width_px; ++u) {
      const Eigen::Vector3d d_C((u - cx) / fx, (v - cy) / fy, 1.0);
      const double length = d_C.norm();
      const std::size_t i = static_cast<std::size_t>(v) * table.width_px + u;
      table.directions_C[i] = (d_C / length).cast<float>();
      table.z_per_t[i] = static_cast<float>(1.0 / length);
    }
  }
  return table;
}

std::vector<Ray> worldRays(const PixelRayTable& table, const Eigen::Isometry3d& T_W_C,
                           float max_t_m, int threads) {
  const Eigen::Matrix3f R_W_C = T_W_C.linear().cast<float>();
  const Eigen::Vector3f origin_W = T_W_C.translation().cast<float>();
  std::vector<Ray> rays(table.directions_C.size());
  parallelForBlocks(table.height_px, threads, [&](int begin, int end) {
    const std::size_t last = static_cast<std::size_t>(end) * table.width_px;
    for (std::size_t i = static_cast<std::size_t>(begin) * table.width_px; i < last; ++i) {
      rays[i] = Ray{origin_W, R_W_C * table.directions_C[i], max_t_m};
    }
  });
  return rays;
}

}  // namespace strata::sim
