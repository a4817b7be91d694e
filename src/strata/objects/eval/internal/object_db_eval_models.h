#pragma once
// Internal to object_db_eval*.cpp: the per-model figures (completeness, accuracy, growth) and
// the pose errors.
#include <map>
#include <utility>
#include <vector>

#include "strata/objects/eval/object_db_eval.h"

namespace strata::eval::detail {

/// (session, segment id) -> the true object the segment lies on (0: none).
using SegmentObjects = std::map<std::pair<int, int>, int>;

/// The true object of an instance's segment (0 when unknown or a false positive).
int instanceObject(const SegmentObjects& segments, const objects::ObjectInstance& instance);

/// Completeness, accuracy and growth of one model.
ModelEvaluation evaluateModel(const objects::ObjectModel& model, const SegmentObjects& segments,
                              const ObjectDbTruth& truth, const ObjectDbEvalConfig& config);

/// Pose errors over every model's instance pairs on one true object; fills the per-model pose
/// figures of `per_model` (one per model, same order) and, in `constrained`, the errors over the
/// pairs of two constrained poses only.
PoseErrors poseErrors(const std::vector<objects::ObjectModel>& models,
                      const SegmentObjects& objects_of, const ObjectDbTruth& truth,
                      std::vector<ModelEvaluation>& per_model, PoseErrors& constrained);

/// Area of the mesh's triangles, leaving out those lying on the floor (every vertex at z <=
/// floor_z_m) when `skip_floor` is set.
double triangleArea(const Mesh& mesh, bool skip_floor, double floor_z_m = 1e-4);

}  // namespace strata::eval::detail
