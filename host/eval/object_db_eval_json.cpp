#include <cstdio>
#include <sstream>

#include "core/json_text.h"
#include "eval/object_db_eval.h"

namespace strata::eval {
namespace {

std::string percent(std::size_t num, std::size_t den) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.1f %% (%zu/%zu)",
                den ? 100.0 * double(num) / double(den) : 100.0, num, den);
  return text;
}

void writeModel(std::ostream& out, const ModelEvaluation& m) {
  out << "{\"model\": " << m.model_id << ", \"object_id\": " << m.object_id
      << ", \"object\": " << jsonQuoted(m.name) << ", \"instances\": " << m.instances
      << ", \"sessions\": " << m.sessions << ", \"area_m2\": " << jsonNumber(m.area_m2)
      << ", \"largest_observation_m2\": " << jsonNumber(m.largest_observation_m2)
      << ", \"completeness\": " << jsonNumber(m.completeness)
      << ", \"true_area_m2\": " << jsonNumber(m.true_area_m2)
      << ", \"growth\": " << jsonNumber(m.growth)
      << ", \"accuracy_m\": " << jsonNumber(m.accuracy_m) << ", \"pose_pairs\": " << m.pose_pairs
      << ", \"pose_max_translation_m\": " << jsonNumber(m.pose_max_translation_m)
      << ", \"pose_max_rotation_deg\": " << jsonNumber(m.pose_max_rotation_deg) << "}";
}

std::string poseJson(const PoseErrors& pose) {
  std::ostringstream out;
  out << "{\"pairs\": " << pose.pairs
      << ", \"median_translation_m\": " << jsonNumber(pose.median_translation_m)
      << ", \"p95_translation_m\": " << jsonNumber(pose.p95_translation_m)
      << ", \"max_translation_m\": " << jsonNumber(pose.max_translation_m)
      << ", \"median_rotation_deg\": " << jsonNumber(pose.median_rotation_deg)
      << ", \"p95_rotation_deg\": " << jsonNumber(pose.p95_rotation_deg)
      << ", \"max_rotation_deg\": " << jsonNumber(pose.max_rotation_deg) << "}";
  return out.str();
}

}  // namespace

std::string objectDbEvaluationJson(const ObjectDbEvaluation& e, int indent) {
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  const PairCounts& p = e.pairs;
  const PoseErrors& pose = e.pose;  // all pairs; pose_constrained: both poses constrained
  std::ostringstream out;
  out << "{\n"
      << pad << "\"segments\": " << e.segments
      << ", \"segments_in_models\": " << e.segments_in_models << ",\n"
      << pad << "\"pairs\": {\"precision\": " << jsonNumber(p.precision())
      << ", \"recall\": " << jsonNumber(p.recall()) << ", \"predicted_same\": " << p.predicted_same
      << ", \"predicted_same_correct\": " << p.predicted_same_correct
      << ", \"same_object\": " << p.same_object
      << ", \"same_object_predicted\": " << p.same_object_predicted
      << ", \"main_recall\": " << jsonNumber(p.mainRecall())
      << ", \"same_object_main\": " << p.same_object_main
      << ", \"same_object_main_predicted\": " << p.same_object_main_predicted
      << ", \"same_shape_other_object\": " << p.same_shape_other_object
      << ", \"same_shape_other_object_predicted\": " << p.same_shape_other_object_predicted
      << "},\n"
      << pad << "\"pose\": " << poseJson(pose) << ",\n"
      << pad << "\"pose_constrained\": " << poseJson(e.pose_constrained) << ",\n"
      << pad << "\"completeness_mean\": " << jsonNumber(e.completeness_mean)
      << ", \"completeness_models\": " << e.completeness_models
      << ", \"accuracy_mean_m\": " << jsonNumber(e.accuracy_mean_m)
      << ", \"accuracy_instances\": " << e.accuracy_instances
      << ", \"growth_max\": " << jsonNumber(e.growth_max)
      << ", \"growth_max_model\": " << e.growth_max_model << ",\n"
      << pad << "\"segments_as\": [";
  for (std::size_t i = 0; i < e.segment_identities.size(); ++i) {
    const SegmentIdentity& s = e.segment_identities[i];
    out << (i ? ", " : "") << "[" << s.session << ", " << s.segment_id << ", " << s.object_id
        << ", " << s.model_id << "]";
  }
  out << "],\n" << pad << "\"models\": [";
  for (std::size_t i = 0; i < e.models.size(); ++i) {
    out << (i ? ",\n" : "\n") << pad << "  ";
    writeModel(out, e.models[i]);
  }
  out << (e.models.empty() ? "]\n" : "\n" + pad + "]\n") << std::string(indent, ' ') << "}";
  return out.str();
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
