#include "strata/mapper/eval/accuracy.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace strata::eval {

TsdfAccuracy evaluateTsdf(const TsdfMap& map, const sim::AnalyticScene& scene, float band_m,
                          float min_weight) {
  return evaluateTsdf(
      map, [&](const Eigen::Vector3d& p) { return scene.signedDistance(p); }, band_m, min_weight);
}

MeshAccuracy evaluateMesh(const Mesh& mesh, const sim::AnalyticScene& scene, float tolerance_m) {
  return evaluateMesh(
      mesh, [&](const Eigen::Vector3d& p) { return scene.signedDistance(p); }, tolerance_m);
}

TsdfAccuracy evaluateTsdf(const TsdfMap& map, const TrueSdf& truth, float band_m,
                          float min_weight) {
  TsdfAccuracy result;
  double sum = 0.0;
  const float voxel_size_m = map.config().voxel_size_m;
  for (const auto& [index, block] : map.blocks()) {
    for (int z = 0; z < kBlockEdge; ++z) {
      for (int y = 0; y < kBlockEdge; ++y) {
        for (int x = 0; x < kBlockEdge; ++x) {
          const TsdfVoxel& voxel = block[linearVoxelIndex(x, y, z)];
          if (voxel.weight < min_weight) continue;
          const Eigen::Vector3f p_W =
              voxelCenter(index * kBlockEdge + Eigen::Vector3i(x, y, z), voxel_size_m);
          const double truth_m = truth(p_W.cast<double>());
          if (std::abs(truth_m) > band_m) continue;
          const double error = std::abs(voxel.tsdf_m - truth_m);
          sum += error;
          result.max_abs_error_m = std::max(result.max_abs_error_m, error);
          ++result.voxels;
        }
      }
    }
  }
  if (result.voxels > 0) result.mean_abs_error_m = sum / static_cast<double>(result.voxels);
  return result;
}

MeshAccuracy evaluateMesh(const Mesh& mesh, const TrueSdf& truth, float tolerance_m) {
  MeshAccuracy result;
  result.vertices = mesh.vertices.size();
  if (mesh.vertices.empty()) return result;
  std::vector<double> distances;
  distances.reserve(mesh.vertices.size());
  double sum = 0.0;
  std::size_t within = 0;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    const double d = std::abs(truth(v.cast<double>()));
    distances.push_back(d);
    sum += d;
    if (d <= tolerance_m) ++within;
  }
  const std::size_t p99 = std::min(distances.size() - 1, distances.size() * 99 / 100);
  std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(p99),
                   distances.end());
  result.p99_distance_m = distances[p99];
  result.mean_distance_m = sum / static_cast<double>(distances.size());
  result.fraction_within = static_cast<double>(within) / static_cast<double>(distances.size());
  return result;
}

}  // namespace strata::eval
