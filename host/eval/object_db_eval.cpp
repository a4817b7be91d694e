#include "eval/object_db_eval.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "eval/object_db_eval_models.h"

namespace strata::eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// One discovered segment: where it is, what it truly is, which model took it.
struct SegmentRow {
  int session = 0;
  int segment_id = 0;
  int object_id = 0;
  int model_id = 0;
  bool main = false;  // the object's segment with the most vertices in its session
};

double angleFromTrace(double trace) {
  return std::acos(std::clamp((trace - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / kPi;
}

/// Value at quantile q (0..1) of `values` (nearest rank; sorts them).
double quantile(std::vector<double>& values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * double(values.size())));
  return values[std::min(values.size() - 1, rank > 0 ? rank - 1 : 0)];
}

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

struct PairError {
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};

/// The errors of the model's instance pairs that lie on one true object.
std::vector<PairError> modelPoseErrors(const objects::ObjectModel& model,
                                       const detail::SegmentObjects& objects_of,
                                       const ObjectDbTruth& truth) {
  std::vector<PairError> errors;
  for (std::size_t i = 0; i < model.instances.size(); ++i) {
    for (std::size_t j = i + 1; j < model.instances.size(); ++j) {
      const objects::ObjectInstance& a = model.instances[i];
      const objects::ObjectInstance& b = model.instances[j];
      const int id = detail::instanceObject(objects_of, a);
      if (id == 0 || id != detail::instanceObject(objects_of, b)) continue;
      const auto k = static_cast<std::size_t>(id - 1);
      const Eigen::Isometry3d& T_W_Oa = truth.sessions[std::size_t(a.session)].objects[k].T_W_O;
      const Eigen::Isometry3d& T_W_Ob = truth.sessions[std::size_t(b.session)].objects[k].T_W_O;
      const Eigen::Isometry3d estimated = a.T_W_M * b.T_W_M.inverse();  // b's place -> a's
      const Eigen::Isometry3d actual = T_W_Oa * T_W_Ob.inverse();
      const Mesh& mesh = truth.meshes_O[k];
      Eigen::Vector3d centre_O = Eigen::Vector3d::Zero();
      if (!mesh.vertices.empty()) {
        Eigen::AlignedBox3d box;
        for (const Eigen::Vector3f& v : mesh.vertices) box.extend(v.cast<double>());
        centre_O = box.center();
      }
      const Eigen::Vector3d centre_W = T_W_Ob * centre_O;
      // In a's object frame the error should be a symmetry of the shape (identity at best).
      const Eigen::Matrix3d R_error = (T_W_Oa.inverse() * estimated * T_W_Ob).linear();
      errors.push_back({(estimated * centre_W - actual * centre_W).norm(),
                        symmetricRotationErrorDeg(R_error, yawSymmetryOrder(truth.shapes[k]))});
    }
  }
  return errors;
}

PoseErrors poseErrors(const std::vector<objects::ObjectModel>& models,
                      const detail::SegmentObjects& objects_of, const ObjectDbTruth& truth,
                      std::vector<ModelEvaluation>& per_model) {
  std::vector<double> translation, rotation;
  for (std::size_t m = 0; m < models.size(); ++m) {
    for (const PairError& pair : modelPoseErrors(models[m], objects_of, truth)) {
      translation.push_back(pair.translation_m);
      rotation.push_back(pair.rotation_deg);
      ModelEvaluation& r = per_model[m];
      ++r.pose_pairs;
      r.pose_max_translation_m = std::max(r.pose_max_translation_m, pair.translation_m);
      r.pose_max_rotation_deg = std::max(r.pose_max_rotation_deg, pair.rotation_deg);
    }
  }
  PoseErrors e;
  e.pairs = translation.size();
  e.median_translation_m = quantile(translation, 0.5);
  e.p95_translation_m = quantile(translation, 0.95);
  e.max_translation_m = translation.empty() ? 0.0 : translation.back();
  e.median_rotation_deg = quantile(rotation, 0.5);
  e.p95_rotation_deg = quantile(rotation, 0.95);
  e.max_rotation_deg = rotation.empty() ? 0.0 : rotation.back();
  return e;
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
    default:
      return true;
  }
}

int yawSymmetryOrder(const sim::ShapeSpec& shape) {
  const bool square = std::abs(shape.size_m.x() - shape.size_m.y()) < 1e-6;
  switch (shape.kind) {
    case sim::ShapeKind::kCylinder:
      return 0;
    case sim::ShapeKind::kBox:
    case sim::ShapeKind::kTable:
      return square ? 4 : 2;
    default:
      return 1;
  }
}

double symmetricRotationErrorDeg(const Eigen::Matrix3d& R, int order) {
  // trace(Rz(-theta) R) = cos(theta) (R00 + R11) + sin(theta) (R10 - R01) + R22.
  const double a = R(0, 0) + R(1, 1), b = R(1, 0) - R(0, 1);
  if (order <= 0) return angleFromTrace(std::hypot(a, b) + R(2, 2));  // best theta, closed form
  double best = 180.0;
  for (int k = 0; k < order; ++k) {
    const double theta = 2.0 * kPi * k / order;
    best = std::min(best, angleFromTrace(std::cos(theta) * a + std::sin(theta) * b + R(2, 2)));
  }
  return best;
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
  e.pose = poseErrors(models, objects_of, truth, e.models);
  e.completeness_mean = e.completeness_models ? completeness_sum / e.completeness_models : 0.0;
  e.accuracy_mean_m = e.accuracy_instances ? accuracy_sum / e.accuracy_instances : 0.0;
  return e;
}

}  // namespace strata::eval
