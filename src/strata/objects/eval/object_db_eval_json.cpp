#include <cstdio>
#include <nlohmann/json.hpp>

#include "strata/objects/eval/object_db_eval.h"

namespace strata::eval {
namespace {

using Json = nlohmann::ordered_json;

std::string percent(std::size_t num, std::size_t den) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.1f %% (%zu/%zu)",
                den ? 100.0 * double(num) / double(den) : 100.0, num, den);
  return text;
}

Json modelJson(const ModelEvaluation& m) {
  Json j;
  j["model"] = m.model_id;
  j["object_id"] = m.object_id;
  j["object"] = m.name;
  j["instances"] = m.instances;
  j["sessions"] = m.sessions;
  j["area_m2"] = m.area_m2;
  j["largest_observation_m2"] = m.largest_observation_m2;
  j["completeness"] = m.completeness;
  j["true_area_m2"] = m.true_area_m2;
  j["growth"] = m.growth;
  j["accuracy_m"] = m.accuracy_m;
  j["pose_pairs"] = m.pose_pairs;
  j["pose_max_translation_m"] = m.pose_max_translation_m;
  j["pose_max_rotation_deg"] = m.pose_max_rotation_deg;
  return j;
}

Json poseJson(const PoseErrors& pose) {
  Json j;
  j["pairs"] = pose.pairs;
  j["median_translation_m"] = pose.median_translation_m;
  j["p95_translation_m"] = pose.p95_translation_m;
  j["max_translation_m"] = pose.max_translation_m;
  j["median_rotation_deg"] = pose.median_rotation_deg;
  j["p95_rotation_deg"] = pose.p95_rotation_deg;
  j["max_rotation_deg"] = pose.max_rotation_deg;
  return j;
}

Json pairsJson(const PairCounts& p) {
  Json j;
  j["precision"] = p.precision();
  j["recall"] = p.recall();
  j["predicted_same"] = p.predicted_same;
  j["predicted_same_correct"] = p.predicted_same_correct;
  j["same_object"] = p.same_object;
  j["same_object_predicted"] = p.same_object_predicted;
  j["main_recall"] = p.mainRecall();
  j["same_object_main"] = p.same_object_main;
  j["same_object_main_predicted"] = p.same_object_main_predicted;
  j["same_shape_other_object"] = p.same_shape_other_object;
  j["same_shape_other_object_predicted"] = p.same_shape_other_object_predicted;
  return j;
}

}  // namespace

std::string objectDbEvaluationJson(const ObjectDbEvaluation& e) {
  Json j;
  j["segments"] = e.segments;
  j["segments_in_models"] = e.segments_in_models;
  j["pairs"] = pairsJson(e.pairs);
  j["pose"] = poseJson(e.pose);  // all pairs; pose_constrained: both poses constrained
  j["pose_constrained"] = poseJson(e.pose_constrained);
  j["completeness_mean"] = e.completeness_mean;
  j["completeness_models"] = e.completeness_models;
  j["accuracy_mean_m"] = e.accuracy_mean_m;
  j["accuracy_instances"] = e.accuracy_instances;
  j["growth_max"] = e.growth_max;
  j["growth_max_model"] = e.growth_max_model;
  Json segments = Json::array();
  for (const SegmentIdentity& s : e.segment_identities) {
    segments.push_back(Json::array({s.session, s.segment_id, s.object_id, s.model_id}));
  }
  j["segments_as"] = std::move(segments);
  Json models = Json::array();
  for (const ModelEvaluation& m : e.models) models.push_back(modelJson(m));
  j["models"] = std::move(models);
  return j.dump(2, ' ', false, Json::error_handler_t::replace);
}

std::string describeObjectDbEvaluation(const ObjectDbEvaluation& e) {
  const PairCounts& p = e.pairs;
  char text[800];
  std::snprintf(text, sizeof(text),
                "pairs: precision %s, recall %s (main segments %s); pose (%zu pairs): median %.1f "
                "mm / %.2f deg, "
                "95th %.1f mm / %.2f deg (constrained poses, %zu pairs: 95th %.1f mm / %.2f "
                "deg); completeness %.2f (%zu models in 3+ sessions); "
                "accuracy %.1f mm; growth at most %.2f",
                percent(p.predicted_same_correct, p.predicted_same).c_str(),
                percent(p.same_object_predicted, p.same_object).c_str(),
                percent(p.same_object_main_predicted, p.same_object_main).c_str(), e.pose.pairs,
                1000.0 * e.pose.median_translation_m, e.pose.median_rotation_deg,
                1000.0 * e.pose.p95_translation_m, e.pose.p95_rotation_deg,
                e.pose_constrained.pairs, 1000.0 * e.pose_constrained.p95_translation_m,
                e.pose_constrained.p95_rotation_deg, e.completeness_mean, e.completeness_models,
                1000.0 * e.accuracy_mean_m, e.growth_max);
  return text;
}

}  // namespace strata::eval
