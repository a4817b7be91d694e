#pragma once
// The object database (objects/object_database.h) scored against a simulated world's truth.
//
// Inputs: every session's discovered segments with the true object each lies on (change::
// evaluateObjects' SegmentMatch::object_id, 0 for a false positive), the truth (every object's
// shape, mesh in its own frame and pose per session) and the database's models with their
// instances (session, segment, T_W_M).
//
// Matching, over pairs of segments. Predicted "same": both segments are instances of one model.
//   precision = predicted-same pairs whose true objects have the same shape (sameShape: identical
//               chairs may share a model) / predicted-same pairs, all pairs (a false-positive
//               segment in a model makes its pairs wrong);
//   recall    = predicted-same pairs / pairs of segments of the SAME true object in different
//               sessions (a segment the database skipped is in no model: its pairs are missed).
//   main recall = the same over each object's main segment per session only (the one with the
//               most vertices): matching apart from over-segmentation (a chair's loose leg).
// Pose, over pairs (i, j) of instances of one model whose segments lie on the same true object:
//   the estimated motion T_W_Mi T_W_Mj^-1 against the true T_W_Oi T_W_Oj^-1; translation error at
//   the object's centre (its true mesh's bounding-box centre, on the symmetry axis), rotation
//   angle modulo the shape's symmetry about its vertical axis (yawSymmetryOrder).
// Completeness, per model: its surface area / the largest observed_area_m2 of its instances (how
//   much merging added to the best single view); the mean over models seen in >= min_sessions.
// Accuracy, per instance on a true object: mean distance of the model's mesh vertices, placed at
//   T_W_M, to the true object's mesh at its true pose in that session (point to triangle).
// Growth ("the ball of doom"), per model: its area / the true area of the object most of its
//   instances lie on (the true mesh without the faces lying on the floor, which no camera sees).
//
// Thread safety: free functions, no shared state.
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "strata/change/eval/evaluation.h"
#include "strata/mesh/mesh.h"
#include "strata/objects/object_model.h"
#include "strata/sim/world/session_truth.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {
class World;
}

namespace strata::eval {

/// The truth the database is scored against; objects are indexed by id - 1 (as in SessionTruth).
struct ObjectDbTruth {
  std::vector<sim::ShapeSpec> shapes;       // by id - 1
  std::vector<std::string> names;           // by id - 1
  std::vector<Mesh> meshes_O;               // by id - 1, object frame
  std::vector<sim::SessionTruth> sessions;  // by session index
  /// Throws InputError when the sizes disagree.
  void validate() const;
};

/// The truth of a simulated world; with `world_sessions`, session i of the database is the
/// world's session world_sessions[i] (InputError for one the world lacks).
ObjectDbTruth objectDbTruth(const sim::World& world, const std::vector<int>& world_sessions = {});

/// Which true object each discovered segment lies on (change::evaluateObjects against every object
/// present in the session, moved or not: a segment of an object change detection should not have
/// reported is still that object). `segments[i]`: database session i's, world session
/// world_sessions[i] (empty: i). Visibility is not needed for the identities and left empty.
std::vector<change::SessionObjectEvaluation> segmentIdentities(
    const sim::World& world, const std::vector<std::vector<change::DiscoveredObject>>& segments,
    const std::vector<int>& world_sessions = {}, const change::EvaluationConfig& config = {});

/// Same shape: same kind and the same size, radius, sides, levels, mesh file, seed (vase, blob,
/// tube), thickness (l_shape, u_shape) or legs (stool); colour aside.
bool sameShape(const sim::ShapeSpec& a, const sim::ShapeSpec& b);

/// Rotations about the object's vertical axis that leave the shape as it is: 0 = any (cylinder),
/// else n (the shape maps onto itself every 360/n degrees): box and table with a square footprint
/// 4, other boxes and tables 2, chair, shelf and meshes 1 (their backs make them asymmetric);
/// procedural shapes as sim::proceduralYawSymmetry (a round vase 0, a round stool its legs).
int yawSymmetryOrder(const sim::ShapeSpec& shape);

/// Rotation angle (degrees) of `R_error` (should be a symmetry of the shape, in its frame) to the
/// nearest rotation about z of the symmetry group of order `order` (yawSymmetryOrder).
double symmetricRotationErrorDeg(const Eigen::Matrix3d& R_error, int order);

struct ObjectDbEvalConfig {
  /// Models seen in at least this many sessions count in the mean completeness.
  int min_sessions = 3;
  /// Model vertices used per instance for the accuracy (evenly strided); bounds the cost.
  std::size_t max_accuracy_vertices = 3000;
  void validate() const;  // InputError naming the bad field
};

struct PairCounts {
  std::size_t predicted_same = 0;              // pairs in one model
  std::size_t predicted_same_correct = 0;      // of those, of the same shape
  std::size_t same_object = 0;                 // pairs of one true object, different sessions
  std::size_t same_object_predicted = 0;       // of those, in one model
  std::size_t same_object_main = 0;            // of same_object, between main segments
  std::size_t same_object_main_predicted = 0;  // of those, in one model
  std::size_t same_shape_other_object = 0;     // pairs of identical, distinct objects
  std::size_t same_shape_other_object_predicted = 0;  // of those, in one model (allowed)
  double precision() const {
    return predicted_same ? double(predicted_same_correct) / double(predicted_same) : 1.0;
  }
  double recall() const {
    return same_object ? double(same_object_predicted) / double(same_object) : 1.0;
  }
  double mainRecall() const {
    return same_object_main ? double(same_object_main_predicted) / double(same_object_main) : 1.0;
  }
};

struct PoseErrors {
  std::size_t pairs = 0;
  double median_translation_m = 0.0;
  double p95_translation_m = 0.0;
  double max_translation_m = 0.0;
  double median_rotation_deg = 0.0;
  double p95_rotation_deg = 0.0;
  double max_rotation_deg = 0.0;
};

struct ModelEvaluation {
  int model_id = 0;
  int object_id = 0;  // the true object most of its instances lie on (0: none)
  std::string name;   // of that object
  int instances = 0;
  int sessions = 0;  // distinct sessions among its instances
  double area_m2 = 0.0;
  double largest_observation_m2 = 0.0;
  double completeness = 0.0;  // area / largest observation
  double true_area_m2 = 0.0;  // of object_id, floor faces left out
  double growth = 0.0;        // area / true area (0 without an object)
  double accuracy_m = 0.0;    // mean over its instances on a true object
  int accuracy_instances = 0;
  int pose_pairs = 0;  // its instance pairs on one true object
  double pose_max_translation_m = 0.0;
  double pose_max_rotation_deg = 0.0;
};

/// One discovered segment: the object it lies on and the model that took it.
struct SegmentIdentity {
  int session = 0;
  int segment_id = 0;
  int object_id = 0;  // 0: none (a false positive)
  int model_id = 0;   // 0: in no model
};

struct ObjectDbEvaluation {
  std::vector<SegmentIdentity> segment_identities;  // every segment, by session
  std::size_t segments = 0;                         // discovered, all sessions
  std::size_t segments_in_models = 0;               // instances of some model
  PairCounts pairs;
  PoseErrors pose;
  /// The same over the pairs whose two instances both have a constrained pose
  /// (ObjectInstance::pose_constrained): what a user who trusts only those flags gets.
  PoseErrors pose_constrained;
  std::vector<ModelEvaluation> models;  // by model id
  std::size_t completeness_models = 0;  // models seen in >= min_sessions
  double completeness_mean = 0.0;
  double accuracy_mean_m = 0.0;  // over instances on a true object
  std::size_t accuracy_instances = 0;
  double growth_max = 0.0;
  int growth_max_model = 0;
};

/// `segments[k]`: one session's SegmentMatch list (its .session names the session). Instances
/// whose (session, segment) is not among them count as segments of no true object. Throws
/// InputError for a session outside the truth or an invalid truth or config.
ObjectDbEvaluation evaluateObjectDatabase(
    const std::vector<change::SessionObjectEvaluation>& segments, const ObjectDbTruth& truth,
    const std::vector<objects::ObjectModel>& models, const ObjectDbEvalConfig& config = {});

/// The evaluation as one JSON object indented by two spaces (no trailing newline); NaN as null.
/// "segments_as" lists every segment as [session, segment, object id, model id].
std::string objectDbEvaluationJson(const ObjectDbEvaluation& evaluation);

/// "pairs: precision 100.0 % (12/12), recall 92.3 % (12/13); pose median 4.1 mm / 0.3 deg ..."
std::string describeObjectDbEvaluation(const ObjectDbEvaluation& evaluation);

}  // namespace strata::eval
