// objects.json's members: the models with their instances, and what happened to every segment.
#include "cli/objects_outputs.h"
#include "cli/report_json.h"

namespace strata::apps {
namespace {

Eigen::Vector3d meshCentroid(const Mesh& mesh) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : mesh.vertices) sum += v.cast<double>();
  return mesh.vertices.empty() ? sum : sum / double(mesh.vertices.size());
}

/// 4x4 as its rows (as the ground truth's objects.json writes T_W_O).
Json matrix4(const Eigen::Isometry3d& T) {
  Json rows = Json::array();
  for (int r = 0; r < 4; ++r) {
    Json row = Json::array();
    for (int c = 0; c < 4; ++c) row.push_back(T.matrix()(r, c));
    rows.push_back(std::move(row));
  }
  return rows;
}

Json instanceJson(const objects::ObjectInstance& inst, const Eigen::Vector3d& centroid_M) {
  Json j;
  j["session"] = inst.session;
  j["segment"] = inst.segment_id;
  j["centroid_m"] = jsonVector(Eigen::Vector3d(inst.T_W_M * centroid_M));
  j["T_W_O"] = matrix4(inst.T_W_M);
  j["match_score"] = inst.match_score;
  j["observed_area_m2"] = jsonFloat(inst.observed_area_m2);
  j["merged"] = inst.merged;
  j["pose_constrained"] = inst.pose_constrained;
  return j;
}

Json modelJson(const objects::ObjectModel& m, const std::string& file) {
  const Eigen::Vector3d centroid_M = meshCentroid(m.mesh_M);
  Json instances = Json::array();
  for (const objects::ObjectInstance& inst : m.instances) {
    instances.push_back(instanceJson(inst, centroid_M));
  }
  Json j;
  j["id"] = m.id;
  j["surface_area_m2"] = jsonFloat(m.surface_area_m2);
  j["merged_observations"] = m.merged_observations;
  j["extent_m"] = jsonVector(m.extent_m);
  j["mesh"] = file;
  j["instances"] = std::move(instances);
  return j;
}

Json outcomeJson(const objects::SegmentOutcome& o) {
  Json j;
  j["session"] = o.session;
  j["segment"] = o.segment_id;
  j["model"] = o.model_id;
  j["new_model"] = o.new_model;
  j["joined_models"] = o.joined_models;
  j["skipped"] = o.skipped;
  j["candidates"] = o.candidates;
  j["registrations"] = o.registrations;
  j["score"] = o.score;
  j["fitness"] = o.registration.fitness;
  j["rmse_m"] = o.registration.rmse_m;
  j["horizontal_constraint"] = o.registration.horizontal_constraint;
  j["agreement"] = o.consistency.agreement;
  j["overlap"] = o.consistency.overlap;
  j["free_space_violation"] = o.consistency.free_space_violation;
  j["refused"] = o.refused;
  j["ms"] = o.ms;
  return j;
}

}  // namespace

std::string objectsJson(const ObjectsRun& run, const ObjectsFiles& files) {
  Json models = Json::array();
  const auto& database_models = run.database.models();
  for (std::size_t i = 0; i < database_models.size(); ++i) {
    models.push_back(modelJson(database_models[i], i < files.models.size() ? files.models[i] : ""));
  }
  Json segments = Json::array();
  for (const auto& session : run.outcomes) {
    for (const objects::SegmentOutcome& o : session) segments.push_back(outcomeJson(o));
  }
  Json j;
  j["build_s"] = run.build_s;
  j["database"] = files.database;
  j["contact_sheet"] = files.contact_sheet;
  j["completed"] = files.completed;
  j["models"] = std::move(models);
  j["segments"] = std::move(segments);
  return jsonText(j);
}

}  // namespace strata::apps
