#pragma once
// Accuracy of a fused map and its mesh against an analytic scene's exact geometry.
#include <cstddef>
#include <functional>

#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"
#include "strata/sim/analytic_scene.h"

namespace strata::eval {

struct TsdfAccuracy {
  std::size_t voxels = 0;          // observed voxels with |true sdf| <= band
  double mean_abs_error_m = 0.0;   // mean |tsdf - true sdf| over them
  double max_abs_error_m = 0.0;
};

/// Exact signed distance of the true scene at a world point.
using TrueSdf = std::function<double(const Eigen::Vector3d&)>;

/// Compares every observed voxel (weight >= min_weight) whose true |sdf| <= band_m.
TsdfAccuracy evaluateTsdf(const TsdfMap& map, const TrueSdf& truth, float band_m,
                          float min_weight = 1e-3f);
TsdfAccuracy evaluateTsdf(const TsdfMap& map, const sim::AnalyticScene& scene, float band_m,
                          float min_weight = 1e-3f);

struct MeshAccuracy {
  std::size_t vertices = 0;
  double mean_distance_m = 0.0;    // mean |true sdf| at the vertices
  double p99_distance_m = 0.0;     // 99th percentile
  double fraction_within = 0.0;    // share of vertices with |sdf| <= tolerance
};

MeshAccuracy evaluateMesh(const Mesh& mesh, const TrueSdf& truth, float tolerance_m);
MeshAccuracy evaluateMesh(const Mesh& mesh, const sim::AnalyticScene& scene, float tolerance_m);

}  // namespace strata::eval
