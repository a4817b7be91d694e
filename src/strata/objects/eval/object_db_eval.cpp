#include "strata/objects/eval/object_db_eval.h"

#include <algorithm>
#include <cmath>

#include "strata/core/error.h"
#include "strata/objects/eval/internal/object_db_eval_models.h"

namespace strata::eval {
namespace {

/// One discovered segment: where it is, what it truly is, which model took it.
struct SegmentRow {
  int session = 0;
  int segment_id = 0;
  int object_id = 0;
  int model_id = 0;
  bool main = false;  // the object's segment with the most vertices in its session
};

/// Marks, among the rows just added for `session`, each object's segment with the most vertices.
void markMainSegments(const change::SessionObjectEvaluation& session,
                      std::vector<SegmentRow>& rows) {
  const std::size_t first = rows.size() - session.segments.size();
  std::map<int, std::size_t> best;  // object id -> index into session.segments
  for (std::size_t k = 0; k < session.segments.size(); ++k) {
    const change::SegmentMatch& m = session.segments[k];
    if (m.object_id == 0) continue;
    const auto it = best.find(m.object_id);
    if (it == best.end() || m.vertices > session.segments[it->second].vertices) {
      best[m.object_id] = k;
    }
  }
  for (const auto& [id, k] : best) rows[first + k].main = true;
}

std::vector<SegmentRow> segmentRows(const std::vector<change::SessionObjectEvaluation>& segments,
                                    const std::vector<objects::ObjectModel>& models,
                                    detail::SegmentObjects& objects_of) {
  std::map<std::pair<int, int>, int> model_of;
  for (const objects::ObjectModel& model : models) {
    for (const objects::ObjectInstance& instance : model.instances) {
      model_of[{instance.session, instance.segment_id}] = model.id;
    }
  }
  std::vector<SegmentRow> rows;
  for (const change::SessionObjectEvaluation& session : segments) {
    for (const change::SegmentMatch& match : session.segments) {
      objects_of[{session.session, match.segment_id}] = match.object_id;
      const auto it = model_of.find({session.session, match.segment_id});
      rows.push_back({session.session, match.segment_id, match.object_id,
                      it == model_of.end() ? 0 : it->second, false});
    }
    markMainSegments(session, rows);
  }
  return rows;
}

PairCounts countPairs(const std::vector<SegmentRow>& rows, const ObjectDbTruth& truth) {
  PairCounts c;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = i + 1; j < rows.size(); ++j) {
      const SegmentRow& a = rows[i];
      const SegmentRow& b = rows[j];
      const bool predicted = a.model_id != 0 && a.model_id == b.model_id;
      const bool known = a.object_id != 0 && b.object_id != 0;
      const bool same_shape = known && sameShape(truth.shapes[std::size_t(a.object_id - 1)],
                                                 truth.shapes[std::size_t(b.object_id - 1)]);
      c.predicted_same += predicted;
      c.predicted_same_correct += predicted && same_shape;
      if (known && a.object_id == b.object_id && a.session != b.session) {
        ++c.same_object;
        c.same_object_predicted += predicted;
        if (a.main && b.main) {
          ++c.same_object_main;
          c.same_object_main_predicted += predicted;
        }
      } else if (same_shape && a.object_id != b.object_id) {
        ++c.same_shape_other_object;
        c.same_shape_other_object_predicted += predicted;
      }
    }
  }
  return c;
}

}  // namespace

void ObjectDbTruth::validate() const {
  if (names.size() != shapes.size() || meshes_O.size() != shapes.size()) {
    throw InputError("object database truth: " + std::to_string(shapes.size()) + " shapes, " +
                     std::to_string(names.size()) + " names and " +
                     std::to_string(meshes_O.size()) + " meshes; one each per object");
  }
  for (const sim::SessionTruth& session : sessions) {
    if (session.objects.size() != shapes.size()) {
      throw InputError("object database truth: session " + std::to_string(session.index) + " has " +
                       std::to_string(session.objects.size()) + " objects, not " +
                       std::to_string(shapes.size()));
    }
  }
}

bool sameShape(const sim::ShapeSpec& a, const sim::ShapeSpec& b) {
  constexpr double kTolerance_m = 1e-6;
  if (a.kind != b.kind || !a.size_m.isApprox(b.size_m, kTolerance_m)) return false;
  switch (a.kind) {
    case sim::ShapeKind::kCylinder:
      return std::abs(a.radius_m - b.radius_m) < kTolerance_m && a.segments == b.segments;
    case sim::ShapeKind::kShelf:
      return a.levels == b.levels;
    case sim::ShapeKind::kMesh:
      return a.mesh_path == b.mesh_path && a.scale == b.scale && a.y_up == b.y_up;
    case sim::ShapeKind::kVase:
    case sim::ShapeKind::kBlob:
    case sim::ShapeKind::kTube:
      return a.seed == b.seed;
    case sim::ShapeKind::kLShape:
    case sim::ShapeKind::kUShape:
      return std::abs(a.thickness_m - b.thickness_m) < kTolerance_m;
    case sim::ShapeKind::kStool:
      return a.legs == b.legs;
    default:
      return true;
  }
}

void ObjectDbEvalConfig::validate() const {
  if (min_sessions < 1) throw InputError("ObjectDbEvalConfig::min_sessions must be >= 1");
  if (max_accuracy_vertices < 1) {
    throw InputError("ObjectDbEvalConfig::max_accuracy_vertices must be >= 1");
  }
}

ObjectDbEvaluation evaluateObjectDatabase(
    const std::vector<change::SessionObjectEvaluation>& segments, const ObjectDbTruth& truth,
    const std::vector<objects::ObjectModel>& models, const ObjectDbEvalConfig& config) {
  truth.validate();
  config.validate();
  const auto checkSession = [&](int session, const char* what) {
    if (session < 0 || static_cast<std::size_t>(session) >= truth.sessions.size()) {
      throw InputError(std::string("object database evaluation: ") + what + " of session " +
                       std::to_string(session) + ", the truth has " +
                       std::to_string(truth.sessions.size()) + " sessions");
    }
  };
  for (const auto& s : segments) {
    checkSession(s.session, "segments");
    for (const auto& m : s.segments) {
      if (m.object_id < 0 || static_cast<std::size_t>(m.object_id) > truth.shapes.size()) {
        throw InputError("object database evaluation: segment " + std::to_string(m.segment_id) +
                         " of session " + std::to_string(s.session) + " lies on object " +
                         std::to_string(m.object_id) + ", which the truth lacks");
      }
    }
  }
  for (const auto& model : models) {
    for (const auto& instance : model.instances) checkSession(instance.session, "an instance");
  }
  ObjectDbEvaluation e;
  detail::SegmentObjects objects_of;
  const std::vector<SegmentRow> rows = segmentRows(segments, models, objects_of);
  e.segments = rows.size();
  for (const SegmentRow& row : rows) {
    e.segments_in_models += row.model_id != 0;
    e.segment_identities.push_back({row.session, row.segment_id, row.object_id, row.model_id});
  }
  e.pairs = countPairs(rows, truth);
  double completeness_sum = 0.0, accuracy_sum = 0.0;
  for (const objects::ObjectModel& model : models) {
    e.models.push_back(detail::evaluateModel(model, objects_of, truth, config));
    const ModelEvaluation& m = e.models.back();
    if (m.sessions >= config.min_sessions) {
      completeness_sum += m.completeness;
      ++e.completeness_models;
    }
    accuracy_sum += m.accuracy_m * m.accuracy_instances;
    e.accuracy_instances += static_cast<std::size_t>(m.accuracy_instances);
    if (m.growth > e.growth_max) e.growth_max = m.growth, e.growth_max_model = m.model_id;
  }
  e.pose = detail::poseErrors(models, objects_of, truth, e.models, e.pose_constrained);
  e.completeness_mean = e.completeness_models ? completeness_sum / e.completeness_models : 0.0;
  e.accuracy_mean_m = e.accuracy_instances ? accuracy_sum / e.accuracy_instances : 0.0;
  return e;
}

}  // namespace strata::eval
