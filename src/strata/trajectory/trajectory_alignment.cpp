#include "strata/trajectory/trajectory_alignment.h"

#include <Eigen/Geometry>
#include <string>

#include "strata/core/error.h"

namespace strata::trajectory {
namespace {

// Below this RMS spread (metres) a trajectory has no extent to fit a scale to.
constexpr double kMinSim3Spread_m = 1e-3;
// Positions fix the rotation about every axis only when they spread across a plane: below this
// ratio of the second to the first principal spread (a near-straight path) the rotation comes
// from the orientations instead.
constexpr double kMinPlanarSpreadRatio = 0.1;

double planarSpreadRatio(const Eigen::Matrix3Xd& p) {
  const Eigen::Matrix3Xd centred = p.colwise() - p.rowwise().mean();
  const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(centred * centred.transpose()).singularValues();
  return sv[0] > 0.0 ? std::sqrt(sv[1] / sv[0]) : 0.0;
}

/// The rotation nearest (chordal L2) to the mean of R_gt_i * R_est_i^T.
Eigen::Matrix3d meanRotation(const std::vector<Eigen::Isometry3d>& estimate,
                             const std::vector<Eigen::Isometry3d>& truth) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < estimate.size(); ++i) sum += truth[i].linear() * estimate[i].linear().transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

/// Scale and translation for a given rotation, least squares over the positions.
void fitScaleAndTranslation(const Eigen::Matrix3Xd& p_est, const Eigen::Matrix3Xd& p_gt,
                            bool with_scale, SimilarityTransform* s) {
  const Eigen::Vector3d mu_est = p_est.rowwise().mean(), mu_gt = p_gt.rowwise().mean();
  const Eigen::Matrix3Xd rotated = s->T_gt_est.linear() * (p_est.colwise() - mu_est);
  s->scale = with_scale ? (p_gt.colwise() - mu_gt).cwiseProduct(rotated).sum() / rotated.squaredNorm() : 1.0;
  s->T_gt_est.translation() = mu_gt - s->scale * (s->T_gt_est.linear() * mu_est);
}

Eigen::Matrix3Xd positions(const std::vector<Eigen::Isometry3d>& poses) {
  Eigen::Matrix3Xd p(3, static_cast<Eigen::Index>(poses.size()));
  for (std::size_t i = 0; i < poses.size(); ++i) p.col(static_cast<Eigen::Index>(i)) = poses[i].translation();
  return p;
}

double rmsSpread(const Eigen::Matrix3Xd& p) {
  const Eigen::Vector3d mean = p.rowwise().mean();
  return std::sqrt((p.colwise() - mean).squaredNorm() / static_cast<double>(p.cols()));
}

}  // namespace

Alignment parseAlignment(const std::string& text) {
  if (text == "none") return Alignment::kNone;
  if (text == "first") return Alignment::kFirstPose;
  if (text == "se3") return Alignment::kSE3;
  if (text == "sim3") return Alignment::kSim3;
  throw InputError("unknown trajectory alignment '" + text + "' (expected none, first, se3 or sim3)");
}

const char* alignmentName(Alignment alignment) {
  switch (alignment) {
    case Alignment::kNone: return "none";
    case Alignment::kFirstPose: return "first";
    case Alignment::kSE3: return "se3";
    case Alignment::kSim3: return "sim3";
  }
  return "?";
}

Eigen::Vector3d SimilarityTransform::apply(const Eigen::Vector3d& p_est) const {
  return scale * (T_gt_est.linear() * p_est) + T_gt_est.translation();
}

Eigen::Isometry3d SimilarityTransform::apply(const Eigen::Isometry3d& T_est_C) const {
  Eigen::Isometry3d T_gt_C = Eigen::Isometry3d::Identity();
  T_gt_C.linear() = T_gt_est.linear() * T_est_C.linear();
  T_gt_C.translation() = apply(T_est_C.translation());
  return T_gt_C;
}

SimilarityTransform alignTrajectory(const std::vector<Eigen::Isometry3d>& estimate,
                                    const std::vector<Eigen::Isometry3d>& truth,
                                    Alignment alignment) {
  if (estimate.empty() || estimate.size() != truth.size()) {
    throw InputError("trajectory alignment needs matched poses: " + std::to_string(estimate.size()) +
                     " estimated, " + std::to_string(truth.size()) + " true");
  }
  SimilarityTransform s;
  switch (alignment) {
    case Alignment::kNone: return s;
    case Alignment::kFirstPose: s.T_gt_est = truth.front() * estimate.front().inverse(); return s;
    case Alignment::kSE3:
    case Alignment::kSim3: break;
  }
  const Eigen::Matrix3Xd p_est = positions(estimate);
  const Eigen::Matrix3Xd p_gt = positions(truth);
  const bool with_scale = alignment == Alignment::kSim3;
  if (with_scale && rmsSpread(p_est) < kMinSim3Spread_m) {
    throw InputError("Sim(3) alignment: the estimated trajectory has no extent (positions within " +
                     std::to_string(kMinSim3Spread_m * 1e3) + " mm), so its scale is unobservable");
  }
  if (planarSpreadRatio(p_est) < kMinPlanarSpreadRatio) {
    s.rotation_from_orientations = true;
    s.T_gt_est.linear() = meanRotation(estimate, truth);
    fitScaleAndTranslation(p_est, p_gt, with_scale, &s);
    return s;
  }
  const Eigen::Matrix4d T = Eigen::umeyama(p_est, p_gt, with_scale);
  // umeyama returns [s R | t]; the scale is the norm of any column of the upper block.
  s.scale = with_scale ? T.block<3, 1>(0, 0).norm() : 1.0;
  s.T_gt_est.linear() = T.block<3, 3>(0, 0) / s.scale;
  s.T_gt_est.translation() = T.block<3, 1>(0, 3);
  return s;
}

}  // namespace strata::trajectory
