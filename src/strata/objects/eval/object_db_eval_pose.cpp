// The pose errors of matched instances, modulo the shapes' symmetry about the vertical.
#include <algorithm>
#include <cmath>

#include "strata/objects/eval/internal/object_db_eval_models.h"
#include "strata/core/math_constants.h"
#include "strata/sim/world/procedural_shapes.h"

namespace strata::eval {
namespace {

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

struct PairError {
  double translation_m = 0.0;
  double rotation_deg = 0.0;
  bool constrained = true;  // both instances' poses
};

/// Median, 95th percentile and maximum of `errors`.
PoseErrors summarise(const std::vector<PairError>& errors) {
  std::vector<double> translation, rotation;
  for (const PairError& pair : errors) {
    translation.push_back(pair.translation_m);
    rotation.push_back(pair.rotation_deg);
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
                        symmetricRotationErrorDeg(R_error, yawSymmetryOrder(truth.shapes[k])),
                        a.pose_constrained && b.pose_constrained});
    }
  }
  return errors;
}

}  // namespace

namespace detail {

PoseErrors poseErrors(const std::vector<objects::ObjectModel>& models,
                      const SegmentObjects& objects_of, const ObjectDbTruth& truth,
                      std::vector<ModelEvaluation>& per_model, PoseErrors& constrained) {
  std::vector<PairError> all, both_constrained;
  for (std::size_t m = 0; m < models.size(); ++m) {
    for (const PairError& pair : modelPoseErrors(models[m], objects_of, truth)) {
      all.push_back(pair);
      if (pair.constrained) both_constrained.push_back(pair);
      ModelEvaluation& r = per_model[m];
      ++r.pose_pairs;
      r.pose_max_translation_m = std::max(r.pose_max_translation_m, pair.translation_m);
      r.pose_max_rotation_deg = std::max(r.pose_max_rotation_deg, pair.rotation_deg);
    }
  }
  constrained = summarise(both_constrained);
  return summarise(all);
}

}  // namespace detail

int yawSymmetryOrder(const sim::ShapeSpec& shape) {
  if (sim::isProcedural(shape.kind)) return sim::proceduralYawSymmetry(shape);
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

}  // namespace strata::eval
