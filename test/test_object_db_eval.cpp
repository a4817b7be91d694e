// The object database's evaluation against truth on constructed inputs with known answers:
// matching precision and recall over segment pairs, pose errors modulo the shapes' symmetry,
// completeness, accuracy and growth.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "strata/core/error.h"
#include "strata/objects/eval/object_db_eval.h"
#include "strata/sim/world/shape_mesh.h"

namespace strata {
namespace {

using eval::ObjectDbEvaluation;
using eval::ObjectDbTruth;

constexpr double kPi = 3.14159265358979323846;

Eigen::Isometry3d floorAt(double x, double y, double yaw_deg) {
  return sim::floorPose(Eigen::Vector2d(x, y), yaw_deg);
}

Eigen::Isometry3d yawBy(double deg) {
  return Eigen::Isometry3d(Eigen::AngleAxisd(deg * kPi / 180.0, Eigen::Vector3d::UnitZ()));
}

sim::ShapeSpec shape(sim::ShapeKind kind, double x, double y, double z) {
  sim::ShapeSpec s;
  s.kind = kind;
  s.size_m = Eigen::Vector3d(x, y, z);
  return s;
}

Mesh meshOf(const sim::ShapeSpec& spec) {
  Mesh mesh;
  for (const Mesh& part : sim::shapeParts(spec)) {
    sim::appendMesh(part, Eigen::Isometry3d::Identity(), {128, 128, 128}, mesh);
  }
  return mesh;
}

/// Four objects in three sessions: two identical chairs (1, 2), a cube (3), a flat box (4).
/// Object k stands at x = k, y = session, yaw 20 * session degrees.
ObjectDbTruth makeTruth() {
  ObjectDbTruth truth;
  truth.shapes = {shape(sim::ShapeKind::kChair, 0.45, 0.45, 0.9),
                  shape(sim::ShapeKind::kChair, 0.45, 0.45, 0.9),
                  shape(sim::ShapeKind::kBox, 0.4, 0.4, 0.4),
                  shape(sim::ShapeKind::kBox, 0.5, 0.3, 0.2)};
  truth.names = {"chair_a", "chair_b", "cube", "flat_box"};
  for (const auto& s : truth.shapes) truth.meshes_O.push_back(meshOf(s));
  for (int session = 0; session < 3; ++session) {
    sim::SessionTruth st;
    st.index = session;
    for (int id = 1; id <= 4; ++id) {
      sim::ObjectState o;
      o.id = id;
      o.present = true;
      o.T_W_O = floorAt(id, session, 20.0 * session);
      st.objects.push_back(o);
    }
    truth.sessions.push_back(st);
  }
  return truth;
}

/// Every object found as segment `id` in every session.
std::vector<change::SessionObjectEvaluation> allSegments() {
  std::vector<change::SessionObjectEvaluation> sessions;
  for (int session = 0; session < 3; ++session) {
    change::SessionObjectEvaluation s;
    s.session = session;
    for (int id = 1; id <= 4; ++id) {
      change::SegmentMatch m;
      m.segment_id = id;
      m.object_id = id;
      s.segments.push_back(m);
    }
    sessions.push_back(s);
  }
  return sessions;
}

objects::ObjectInstance instance(int session, int segment, const Eigen::Isometry3d& T_W_M,
                                 float area_m2 = 0.1f) {
  objects::ObjectInstance i;
  i.session = session;
  i.segment_id = segment;
  i.T_W_M = T_W_M;
  i.observed_area_m2 = area_m2;
  return i;
}

/// A model of object `id` in its true object frame (M = O), seen in `sessions` at the truth.
objects::ObjectModel perfectModel(int model_id, int id, const ObjectDbTruth& truth,
                                  const std::vector<int>& sessions) {
  objects::ObjectModel m;
  m.id = model_id;
  m.mesh_M = truth.meshes_O[std::size_t(id - 1)];
  for (int s : sessions) {
    m.instances.push_back(instance(s, id, truth.sessions[std::size_t(s)].objects[id - 1].T_W_O));
  }
  return m;
}

TEST(ObjectDbEval, SymmetryOrdersFollowTheShapes) {
  EXPECT_EQ(eval::yawSymmetryOrder(shape(sim::ShapeKind::kBox, 0.4, 0.4, 0.4)), 4);
  EXPECT_EQ(eval::yawSymmetryOrder(shape(sim::ShapeKind::kBox, 0.5, 0.4, 0.4)), 2);
  EXPECT_EQ(eval::yawSymmetryOrder(shape(sim::ShapeKind::kTable, 1.2, 0.7, 0.75)), 2);
  EXPECT_EQ(eval::yawSymmetryOrder(shape(sim::ShapeKind::kCylinder, 0.4, 0.4, 1.0)), 0);
  EXPECT_EQ(eval::yawSymmetryOrder(shape(sim::ShapeKind::kChair, 0.45, 0.45, 0.9)), 1);
  EXPECT_EQ(eval::yawSymmetryOrder(shape(sim::ShapeKind::kShelf, 0.8, 0.35, 1.0)), 1);
  const Eigen::Matrix3d quarter = yawBy(90).linear();
  EXPECT_NEAR(eval::symmetricRotationErrorDeg(quarter, 4), 0.0, 1e-6);
  EXPECT_NEAR(eval::symmetricRotationErrorDeg(quarter, 2), 90.0, 1e-6);
  EXPECT_NEAR(eval::symmetricRotationErrorDeg(quarter, 1), 90.0, 1e-6);
  EXPECT_NEAR(eval::symmetricRotationErrorDeg(yawBy(37).linear(), 0), 0.0, 1e-6);
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(5.0 * kPi / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_NEAR(eval::symmetricRotationErrorDeg(yawBy(37).linear() * tilt, 0), 5.0, 1e-6);
  EXPECT_NEAR(eval::symmetricRotationErrorDeg(yawBy(93).linear(), 4), 3.0, 1e-6);
}

TEST(ObjectDbEval, PerfectDatabaseScoresPerfectly) {
  const ObjectDbTruth truth = makeTruth();
  std::vector<objects::ObjectModel> models;
  for (int id = 1; id <= 4; ++id) models.push_back(perfectModel(id, id, truth, {0, 1, 2}));
  const ObjectDbEvaluation e = eval::evaluateObjectDatabase(allSegments(), truth, models);
  EXPECT_EQ(e.segments, 12u);
  EXPECT_EQ(e.segments_in_models, 12u);
  EXPECT_EQ(e.pairs.same_object, 12u);  // 4 objects x 3 pairs of sessions
  EXPECT_EQ(e.pairs.predicted_same, 12u);
  EXPECT_DOUBLE_EQ(e.pairs.precision(), 1.0);
  EXPECT_DOUBLE_EQ(e.pairs.recall(), 1.0);
  EXPECT_EQ(e.pairs.same_shape_other_object, 9u);  // chair_a x chair_b in 3 x 3 sessions
  EXPECT_EQ(e.pairs.same_shape_other_object_predicted, 0u);
  EXPECT_EQ(e.pose.pairs, 12u);
  EXPECT_LT(e.pose.max_translation_m, 1e-6);
  EXPECT_LT(e.pose.max_rotation_deg, 1e-3);
  EXPECT_LT(e.accuracy_mean_m, 1e-5);
  EXPECT_EQ(e.accuracy_instances, 12u);
  // The cube's model area counts its bottom, the true area does not: 6 / 5 faces.
  ASSERT_EQ(e.models.size(), 4u);
  EXPECT_EQ(e.models[2].object_id, 3);
  EXPECT_NEAR(e.models[2].growth, 6.0 / 5.0, 1e-4);
  EXPECT_NEAR(e.models[2].completeness, 6 * 0.16 / 0.1, 1e-3);  // area / largest observation
  EXPECT_EQ(e.completeness_models, 4u);
  EXPECT_GT(e.growth_max, 1.0);
  const std::string json = eval::objectDbEvaluationJson(e);
  EXPECT_EQ(nlohmann::json::parse(json).at("pairs").at("precision"), 1.0) << json;
  EXPECT_NE(eval::describeObjectDbEvaluation(e).find("precision 100.0 % (12/12)"),
            std::string::npos);
}

TEST(ObjectDbEval, WrongMergeLowersPrecisionIdenticalShapesDoNot) {
  const ObjectDbTruth truth = makeTruth();
  // Model 1 takes chair_a in sessions 0-2 and chair_b in session 0 (identical: allowed);
  // model 2 takes the cube in 0-2 and, wrongly, the flat box of session 1.
  objects::ObjectModel chairs = perfectModel(1, 1, truth, {0, 1, 2});
  chairs.instances.push_back(instance(0, 2, truth.sessions[0].objects[1].T_W_O));
  objects::ObjectModel cube = perfectModel(2, 3, truth, {0, 1, 2});
  cube.instances.push_back(instance(1, 4, truth.sessions[1].objects[3].T_W_O));
  const ObjectDbEvaluation e = eval::evaluateObjectDatabase(allSegments(), truth, {chairs, cube});
  // Predicted pairs: 6 in each model; the 3 cube-flat box pairs are wrong.
  EXPECT_EQ(e.pairs.predicted_same, 12u);
  EXPECT_EQ(e.pairs.predicted_same_correct, 9u);
  EXPECT_DOUBLE_EQ(e.pairs.precision(), 0.75);
  EXPECT_EQ(e.pairs.same_shape_other_object_predicted, 3u);
  // Same-object pairs: 12, of which chair_a's 3 and the cube's 3 are in one model.
  EXPECT_EQ(e.pairs.same_object_predicted, 6u);
  EXPECT_DOUBLE_EQ(e.pairs.recall(), 0.5);
  // Segments the database skipped (chair_b, flat box elsewhere) are in no model.
  EXPECT_EQ(e.segments_in_models, 8u);
  // Growth follows the model's majority object (the cube), not the flat box.
  EXPECT_EQ(e.models[1].object_id, 3);
  EXPECT_EQ(e.models[1].name, "cube");
}

TEST(ObjectDbEval, SymmetricYawIsNoErrorOtherYawIs) {
  const ObjectDbTruth truth = makeTruth();
  // The cube's model placed a quarter turn off in session 1: the cube looks the same.
  objects::ObjectModel cube = perfectModel(1, 3, truth, {0, 1});
  cube.instances[1].T_W_M = cube.instances[1].T_W_M * yawBy(90);
  // The flat box's a quarter turn off (wrong) and a half turn off (the same) in sessions 1, 2.
  objects::ObjectModel flat = perfectModel(2, 4, truth, {0, 1, 2});
  flat.instances[1].T_W_M = flat.instances[1].T_W_M * yawBy(90);
  flat.instances[2].T_W_M = flat.instances[2].T_W_M * yawBy(180);
  const ObjectDbEvaluation cube_only = eval::evaluateObjectDatabase(allSegments(), truth, {cube});
  EXPECT_EQ(cube_only.pose.pairs, 1u);
  EXPECT_LT(cube_only.pose.max_rotation_deg, 1e-3);
  EXPECT_LT(cube_only.pose.max_translation_m, 1e-6);  // turning about its axis keeps the centre
  EXPECT_LT(cube_only.accuracy_mean_m, 1e-5);
  const ObjectDbEvaluation flat_only = eval::evaluateObjectDatabase(allSegments(), truth, {flat});
  // Pairs (0,1): 90; (0,2): 180 = 0; (1,2): 90.
  EXPECT_EQ(flat_only.pose.pairs, 3u);
  EXPECT_NEAR(flat_only.pose.median_rotation_deg, 90.0, 1e-6);
  EXPECT_NEAR(flat_only.pose.max_rotation_deg, 90.0, 1e-6);
  EXPECT_GT(flat_only.accuracy_mean_m, 0.01) << "a quarter turn puts the flat box's ends off";
}

TEST(ObjectDbEval, PoseErrorMeasuredAtTheObjectCentre) {
  const ObjectDbTruth truth = makeTruth();
  objects::ObjectModel chair = perfectModel(1, 1, truth, {0, 1, 2});
  // Session 2's instance 1 cm off along world x; session 1's turned 2 degrees about its origin
  // (the footprint centre, below the centre: no translation at the centre).
  chair.instances[2].T_W_M = Eigen::Translation3d(0.01, 0, 0) * chair.instances[2].T_W_M;
  chair.instances[1].T_W_M = chair.instances[1].T_W_M * yawBy(2);
  const ObjectDbEvaluation e = eval::evaluateObjectDatabase(allSegments(), truth, {chair});
  ASSERT_EQ(e.pose.pairs, 3u);
  // (0,1): 0 m / 2 deg; (0,2): 1 cm / 0 deg; (1,2): 1 cm / 2 deg.
  EXPECT_NEAR(e.pose.median_translation_m, 0.01, 1e-6);
  EXPECT_NEAR(e.pose.max_translation_m, 0.01, 1e-6);
  EXPECT_NEAR(e.pose.median_rotation_deg, 2.0, 1e-6);
  EXPECT_EQ(e.models[0].pose_pairs, 3);
  EXPECT_NEAR(e.models[0].pose_max_translation_m, 0.01, 1e-6);
  EXPECT_NEAR(e.models[0].pose_max_rotation_deg, 2.0, 1e-6);
  // Mean over the instances: 0 (session 0), up to 0.2 m x 2 deg = 7 mm (1), up to 1 cm (2).
  EXPECT_GT(e.models[0].accuracy_m, 0.001);
  EXPECT_LT(e.models[0].accuracy_m, (0.007 + 0.01) / 3);
}

TEST(ObjectDbEval, MainRecallLeavesOverSegmentedFragmentsOut) {
  const ObjectDbTruth truth = makeTruth();
  auto segments = allSegments();
  for (auto& s : segments) {
    for (auto& m : s.segments) m.vertices = 1000;
  }
  // Session 1 sees a loose leg of chair_a as a small segment of its own, in no model.
  change::SegmentMatch leg;
  leg.segment_id = 8;
  leg.object_id = 1;
  leg.vertices = 50;
  segments[1].segments.push_back(leg);
  const objects::ObjectModel chair = perfectModel(1, 1, truth, {0, 1, 2});
  const ObjectDbEvaluation e = eval::evaluateObjectDatabase(segments, truth, {chair});
  // chair_a: 3 pairs between its main segments + the leg with sessions 0 and 2; others: 9.
  EXPECT_EQ(e.pairs.same_object, 14u);
  EXPECT_EQ(e.pairs.same_object_predicted, 3u);
  EXPECT_EQ(e.pairs.same_object_main, 12u);
  EXPECT_EQ(e.pairs.same_object_main_predicted, 3u);
  EXPECT_DOUBLE_EQ(e.pairs.mainRecall(), 0.25);
  ASSERT_EQ(e.models.size(), 1u);
  EXPECT_EQ(e.models[0].pose_pairs, 3);
  EXPECT_LT(e.models[0].pose_max_rotation_deg, 1e-3);
}

TEST(ObjectDbEval, FalsePositiveSegmentInAModelIsWrong) {
  const ObjectDbTruth truth = makeTruth();
  auto segments = allSegments();
  change::SegmentMatch ghost;
  ghost.segment_id = 9;
  ghost.object_id = 0;
  segments[2].segments.push_back(ghost);
  objects::ObjectModel cube = perfectModel(1, 3, truth, {0, 1});
  cube.instances.push_back(instance(2, 9, Eigen::Isometry3d::Identity()));
  const ObjectDbEvaluation e = eval::evaluateObjectDatabase(segments, truth, {cube});
  EXPECT_EQ(e.segments, 13u);
  EXPECT_EQ(e.pairs.predicted_same, 3u);
  EXPECT_EQ(e.pairs.predicted_same_correct, 1u);
  EXPECT_EQ(e.pose.pairs, 1u) << "the ghost has no true pose";
  ASSERT_EQ(e.segment_identities.size(), 13u);
  const eval::SegmentIdentity& last = e.segment_identities.back();
  EXPECT_EQ(last.session, 2);
  EXPECT_EQ(last.segment_id, 9);
  EXPECT_EQ(last.object_id, 0);
  EXPECT_EQ(last.model_id, 1);
  EXPECT_EQ(nlohmann::json::parse(eval::objectDbEvaluationJson(e)).at("segments_as").back(),
            nlohmann::json({2, 9, 0, 1}));
}

TEST(ObjectDbEval, BadInputIsNamed) {
  const ObjectDbTruth truth = makeTruth();
  objects::ObjectModel cube = perfectModel(1, 3, truth, {0});
  cube.instances[0].session = 7;
  try {
    eval::evaluateObjectDatabase(allSegments(), truth, {cube});
    FAIL() << "session 7 is outside the truth";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("session 7"), std::string::npos) << e.what();
  }
  ObjectDbTruth short_truth = truth;
  short_truth.names.pop_back();
  EXPECT_THROW(eval::evaluateObjectDatabase(allSegments(), short_truth, {}), InputError);
  eval::ObjectDbEvalConfig config;
  config.min_sessions = 0;
  EXPECT_THROW(eval::evaluateObjectDatabase(allSegments(), truth, {}, config), InputError);
}

}  // namespace
}  // namespace strata
