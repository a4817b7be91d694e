// Readouts of the occupancy comparison (occupancy_compare.h): true surface points and a cube mesh
// of the occupied voxels.
#include <array>

#include "strata/occupancy/eval/occupancy_compare.h"

namespace strata::eval {

std::vector<Eigen::Vector3f> trueSurfacePoints(const RgbdFrame& frame, const CameraIntrinsics& in,
                                               int stride, float min_depth_m, float max_depth_m) {
  std::vector<Eigen::Vector3f> points;
  const Eigen::Isometry3f T_W_C = frame.T_W_C.cast<float>();
  // From pixel (1, 1): with an even ray stride the truth then lies between the rays.
  const int first = stride > 1 ? 1 : 0;
  for (int v = first; v < frame.depth.height_px; v += stride) {
    for (int u = first; u < frame.depth.width_px; u += stride) {
      const float z = frame.depth.at(u, v);
      if (!(z >= min_depth_m && z <= max_depth_m)) continue;  // outside what either map sees
      const Eigen::Vector3f p_C((u - in.cx_px) / in.fx_px * z, (v - in.cy_px) / in.fy_px * z, z);
      points.push_back(T_W_C * p_C);
    }
  }
  return points;
}

Mesh occupiedVoxelMesh(const OccupancyMap& map, const OccupancyLogOdds& l) {
  // Corner c of the unit cube at bits (x, y, z) of c; faces wound outwards.
  static constexpr std::array<std::array<int, 4>, 6> kFaces{
      {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};
  Mesh mesh;
  const float h = 0.5f * map.voxelSize();
  for (const Eigen::Vector3f& centre : occupiedVoxelCentres(map, l)) {
    const int base = static_cast<int>(mesh.vertices.size());
    for (int c = 0; c < 8; ++c) {
      mesh.vertices.push_back(
          centre + Eigen::Vector3f((c & 1) ? h : -h, (c & 2) ? h : -h, (c & 4) ? h : -h));
    }
    for (const auto& f : kFaces) {
      mesh.triangles.emplace_back(base + f[0], base + f[1], base + f[2]);
      mesh.triangles.emplace_back(base + f[0], base + f[2], base + f[3]);
    }
  }
  return mesh;
}

}  // namespace strata::eval
