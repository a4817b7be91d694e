// objects.json's members: the models with their instances, and what happened to every segment.
#include <sstream>

#include "cli/objects_outputs.h"
#include "core/json_text.h"

namespace strata::apps {
namespace {

Eigen::Vector3d meshCentroid(const Mesh& mesh) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : mesh.vertices) sum += v.cast<double>();
  return mesh.vertices.empty() ? sum : sum / double(mesh.vertices.size());
}

std::string vector3(const Eigen::Vector3d& v) {
  return "[" + jsonNumber(v.x()) + ", " + jsonNumber(v.y()) + ", " + jsonNumber(v.z()) + "]";
}

/// 4x4 as its rows (as the ground truth's objects.json writes T_W_O).
std::string matrix4(const Eigen::Isometry3d& T) {
  std::string text = "[";
  for (int r = 0; r < 4; ++r) {
    text += r ? ", [" : "[";
    for (int c = 0; c < 4; ++c) text += (c ? ", " : "") + jsonNumber(T.matrix()(r, c));
    text += "]";
  }
  return text + "]";
}

void writeModel(std::ostream& out, const objects::ObjectModel& m, const std::string& file,
                const std::string& pad) {
  const Eigen::Vector3d centroid_M = meshCentroid(m.mesh_M);
  out << pad << "{\"id\": " << m.id << ", \"surface_area_m2\": " << jsonNumber(m.surface_area_m2)
      << ", \"merged_observations\": " << m.merged_observations
      << ", \"extent_m\": " << vector3(m.extent_m.cast<double>())
      << ", \"mesh\": " << jsonQuoted(file) << ", \"instances\": [";
  for (std::size_t i = 0; i < m.instances.size(); ++i) {
    const objects::ObjectInstance& inst = m.instances[i];
    out << (i ? ",\n" : "\n") << pad << "  {\"session\": " << inst.session
        << ", \"segment\": " << inst.segment_id
        << ", \"centroid_m\": " << vector3(inst.T_W_M * centroid_M)
        << ", \"T_W_O\": " << matrix4(inst.T_W_M)
        << ", \"match_score\": " << jsonNumber(inst.match_score)
        << ", \"observed_area_m2\": " << jsonNumber(inst.observed_area_m2)
        << ", \"merged\": " << (inst.merged ? "true" : "false")
        << ", \"pose_constrained\": " << (inst.pose_constrained ? "true" : "false") << "}";
  }
  out << "]}";
}

void writeOutcome(std::ostream& out, const objects::SegmentOutcome& o, const std::string& pad) {
  out << pad << "{\"session\": " << o.session << ", \"segment\": " << o.segment_id
      << ", \"model\": " << o.model_id << ", \"new_model\": " << (o.new_model ? "true" : "false")
      << ", \"joined_models\": [";
  for (std::size_t i = 0; i < o.joined_models.size(); ++i) {
    out << (i ? ", " : "") << o.joined_models[i];
  }
  out << "]"
      << ", \"skipped\": " << jsonQuoted(o.skipped) << ", \"candidates\": " << o.candidates
      << ", \"registrations\": " << o.registrations << ", \"score\": " << jsonNumber(o.score)
      << ", \"fitness\": " << jsonNumber(o.registration.fitness)
      << ", \"rmse_m\": " << jsonNumber(o.registration.rmse_m)
      << ", \"horizontal_constraint\": " << jsonNumber(o.registration.horizontal_constraint)
      << ", \"agreement\": " << jsonNumber(o.consistency.agreement)
      << ", \"overlap\": " << jsonNumber(o.consistency.overlap)
      << ", \"free_space_violation\": " << jsonNumber(o.consistency.free_space_violation)
      << ", \"refused\": " << jsonQuoted(o.refused) << ", \"ms\": " << jsonNumber(o.ms) << "}";
}

}  // namespace

std::string objectsJsonMembers(const ObjectsRun& run, const ObjectsFiles& files, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::ostringstream out;
  out << pad << "\"build_s\": " << jsonNumber(run.build_s) << ",\n"
      << pad << "\"database\": " << jsonQuoted(files.database) << ",\n"
      << pad << "\"contact_sheet\": " << jsonQuoted(files.contact_sheet) << ",\n"
      << pad << "\"completed\": [";
  for (std::size_t s = 0; s < files.completed.size(); ++s) {
    out << (s ? ", " : "") << jsonQuoted(files.completed[s]);
  }
  out << "],\n" << pad << "\"models\": [";
  const auto& models = run.database.models();
  for (std::size_t i = 0; i < models.size(); ++i) {
    out << (i ? ",\n" : "\n");
    writeModel(out, models[i], i < files.models.size() ? files.models[i] : "", pad + "  ");
  }
  out << (models.empty() ? "" : "\n" + pad) << "],\n" << pad << "\"segments\": [";
  bool first = true;
  for (const auto& session : run.outcomes) {
    for (const objects::SegmentOutcome& o : session) {
      out << (first ? "\n" : ",\n");
      writeOutcome(out, o, pad + "  ");
      first = false;
    }
  }
  out << (first ? "" : "\n" + pad) << "]";
  return out.str();
}

}  // namespace strata::apps
