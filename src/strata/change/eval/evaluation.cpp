// Evaluation config and the static map's quality (definitions in evaluation.h).
#include "strata/change/eval/evaluation.h"

#include <cmath>

#include "strata/change/eval/internal/evaluation_surface_index.h"
#include "strata/core/error.h"
#include "strata/core/validate.h"

namespace strata::change {
namespace {

void requireShare(float value, const char* field) {
  if (!std::isfinite(value) || value < 0.0f || value > 1.0f) {
    throw InputError(std::string("invalid evaluation config: ") + field + " must be in [0, 1]");
  }
}

}  // namespace

void EvaluationConfig::validate() const {
  requirePositive(match_distance_m, "EvaluationConfig", "match_distance_m");
  requirePositive(static_tolerance_m, "EvaluationConfig", "static_tolerance_m");
  requireShare(found_min_coverage, "found_min_coverage");
  requireShare(found_min_on_object, "found_min_on_object");
  requireShare(segment_min_on_object, "segment_min_on_object");
  requireShare(under_segment_min_share, "under_segment_min_share");
  if (min_views < 1) throw InputError("invalid evaluation config: min_views must be >= 1");
  if (!std::isfinite(min_visible_area_m2) || min_visible_area_m2 < 0.0f) {
    throw InputError("invalid evaluation config: min_visible_area_m2 must be >= 0");
  }
}

StaticMapEvaluation evaluateStaticMap(const Mesh& static_mesh, const Mesh& static_truth,
                                      const std::vector<Mesh>& moved_truth,
                                      const std::vector<Eigen::Vector3f>& seen_static,
                                      const EvaluationConfig& config) {
  config.validate();
  StaticMapEvaluation result;
  result.seen_points = seen_static.size();
  SurfaceIndex reconstructed(config.static_tolerance_m);
  reconstructed.add(static_mesh);
  result.completeness = shareWithin(seen_static, reconstructed, config.static_tolerance_m);
  SurfaceIndex truth(config.match_distance_m), moved(config.match_distance_m);
  truth.add(static_truth);
  for (const Mesh& mesh : moved_truth) moved.add(mesh);
  for (const Eigen::Vector3i& t : static_mesh.triangles) {
    const Eigen::Vector3f& a = static_mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3f& b = static_mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3f& c = static_mesh.vertices[static_cast<std::size_t>(t[2])];
    const double area = 0.5 * static_cast<double>((b - a).cross(c - a).norm());
    result.mesh_area_m2 += area;
    const Eigen::Vector3f centroid = (a + b + c) / 3.0f;
    // Where a moved object stood on the floor both surfaces meet: the static truth wins there.
    if (moved.within(centroid, config.match_distance_m) &&
        !truth.within(centroid, config.match_distance_m)) {
      result.ghost_area_m2 += area;
    }
  }
  return result;
}

}  // namespace strata::change
