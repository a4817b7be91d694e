#pragma once
// Pinhole ray generation shared by the RGB-D and grey cameras.
#include <Eigen/Geometry>
#include <vector>

#include "strata/core/types.h"
#include "strata/sim/ray_scene.h"

namespace strata::sim {

/// Camera-frame rays of every pixel, row-major, computed once per camera: pixel (u, v) looks
/// through its centre along d_C = ((u - cx) / fx, (v - cy) / fy, 1) / |...|. `z_per_t[i]` =
/// 1 / |(..., 1)|: the camera-frame depth per metre along ray i, so a hit at distance t has
/// depth z = t * z_per_t[i].
struct PixelRayTable {
  int width_px = 0;
  int height_px = 0;
  std::vector<Eigen::Vector3f> directions_C;
  std::vector<float> z_per_t;
};

/// Validates the intrinsics (InputError) and builds the table.
PixelRayTable makePixelRayTable(const CameraIntrinsics& intrinsics);

/// The table's rays in the world from camera pose T_W_C (origin at the camera centre), each with
/// max_t_m. `threads` as parallelForBlocks (strata/core/parallel_for.h).
std::vector<Ray> worldRays(const PixelRayTable& table, const Eigen::Isometry3d& T_W_C,
                           float max_t_m, int threads);

}  // namespace strata::sim
