// Odometry fused with localisations: a Kalman filter on the correction T_W_O.
#include "strata/localize/pose_fusion.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "strata/core/error.h"

namespace strata::localize {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Vector3d logRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d expRotation(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, r / angle).toRotationMatrix();
}

/// x -> R(r) (x - c) + c + t: the correction's perturbation about the centre c.
Eigen::Isometry3d perturbation(const Eigen::Matrix<double, 6, 1>& delta, const Eigen::Vector3d& c) {
  Eigen::Isometry3d G = Eigen::Isometry3d::Identity();
  G.linear() = expRotation(delta.tail<3>());
  G.translation() = c - G.linear() * c + delta.head<3>();
  return G;
}

/// A localisation's covariance (camera-frame right perturbation) in map axes about the camera
/// centre, floored.
Matrix6d measurementCovariance(const Localization& l, const FusionConfig& config) {
  Matrix6d A = Matrix6d::Zero();
  A.topLeftCorner<3, 3>() = l.T_W_C.linear();
  A.bottomRightCorner<3, 3>() = l.T_W_C.linear();
  Matrix6d R = A * l.covariance * A.transpose();
  R = 0.5 * (R + R.transpose());
  for (int i = 0; i < 3; ++i) {
    R(i, i) += config.min_localization_sigma_m * config.min_localization_sigma_m;
    R(i + 3, i + 3) += config.min_localization_sigma_rad * config.min_localization_sigma_rad;
  }
  return R;
}

}  // namespace

const char* fusionStatusName(FusionStatus status) {
  switch (status) {
    case FusionStatus::kUninitialised: return "uninitialised";
    case FusionStatus::kTracking: return "tracking";
    case FusionStatus::kCorrected: return "corrected";
  }
  return "?";
}

void FusionConfig::validate() const {
  auto nonNegative = [](double v, const char* name) {
    if (!(v >= 0.0) || !std::isfinite(v))
      throw InputError(std::string("fusion: ") + name + " must be finite and >= 0");
  };
  nonNegative(translation_variance_per_m, "translation_variance_per_m");
  nonNegative(rotation_variance_per_m, "rotation_variance_per_m");
  nonNegative(translation_variance_per_s, "translation_variance_per_s");
  nonNegative(rotation_variance_per_s, "rotation_variance_per_s");
  nonNegative(init_max_disagreement_m, "init_max_disagreement_m");
  nonNegative(init_max_disagreement_rad, "init_max_disagreement_rad");
  if (!(min_localization_sigma_m > 0.0) || !(min_localization_sigma_rad > 0.0))
    throw InputError("fusion: min_localization_sigma_m and _rad must be > 0");
  if (!(gate_chi2 > 0.0)) throw InputError("fusion: gate_chi2 must be > 0");
  if (init_agreeing < 1) throw InputError("fusion: init_agreeing must be >= 1");
  if (reset_after_rejections < 1) throw InputError("fusion: reset_after_rejections must be >= 1");
}

PoseFusion::PoseFusion(const FusionConfig& config) : config_(config) { config_.validate(); }

void PoseFusion::reset() {
  initialised_ = false;
  T_W_O_ = Eigen::Isometry3d::Identity();
  P_.setZero();
  init_candidates_.clear();
  rejections_in_a_row_ = 0;
}

FusedPose PoseFusion::current(FusionStatus status) const {
  FusedPose out;
  if (!initialised_) return out;
  out.status = status;
  out.T_W_C = T_W_O_ * T_O_C_;
  out.covariance = P_;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(P_.topLeftCorner<3, 3>());
  out.translation_sigma_m = std::sqrt(std::max(0.0, eigen.eigenvalues().maxCoeff()));
  return out;
}

std::optional<PosePrior> PoseFusion::prior() const {
  if (!initialised_ || !have_odometry_) return std::nullopt;
  return PosePrior{T_W_O_ * T_O_C_};
}

FusedPose PoseFusion::predict(double timestamp_s, const Eigen::Isometry3d& T_O_C) {
  if (!std::isfinite(timestamp_s) || !T_O_C.matrix().allFinite())
    throw InputError("fusion: odometry pose or timestamp is not finite");
  if (have_odometry_ && timestamp_s < last_time_s_) {
    throw InputError("fusion: odometry time goes backwards (" + std::to_string(timestamp_s) +
                     " s after " + std::to_string(last_time_s_) + " s)");
  }
  if (have_odometry_ && initialised_) {
    const double distance = (T_O_C.translation() - T_O_C_.translation()).norm();
    const double dt = timestamp_s - last_time_s_;
    const Eigen::Vector3d c0 = T_W_O_ * T_O_C_.translation();
    const Eigen::Vector3d c1 = T_W_O_ * T_O_C.translation();
    Matrix6d F = Matrix6d::Identity();
    F.topRightCorner<3, 3>() = -skew(c1 - c0);
    P_ = F * P_ * F.transpose();
    const double qt = config_.translation_variance_per_m * distance +
                      config_.translation_variance_per_s * dt;
    const double qr = config_.rotation_variance_per_m * distance +
                      config_.rotation_variance_per_s * dt;
    for (int i = 0; i < 3; ++i) {
      P_(i, i) += qt;
      P_(i + 3, i + 3) += qr;
    }
  }
  have_odometry_ = true;
  last_time_s_ = timestamp_s;
  T_O_C_ = T_O_C;
  return current(FusionStatus::kTracking);
}

bool PoseFusion::tryInitialise(const Localization& l, std::string& note) {
  const Eigen::Isometry3d candidate = l.T_W_C * T_O_C_.inverse();
  const Eigen::Vector3d c = T_O_C_.translation();
  int agreeing = 1;
  for (const Eigen::Isometry3d& other : init_candidates_) {
    const double dt = (candidate * c - other * c).norm();
    const double dr = Eigen::AngleAxisd(candidate.linear() * other.linear().transpose()).angle();
    if (dt <= config_.init_max_disagreement_m && dr <= config_.init_max_disagreement_rad) ++agreeing;
  }
  init_candidates_.push_back(candidate);
  while (init_candidates_.size() > 6) init_candidates_.pop_front();
  if (agreeing < config_.init_agreeing) {
    note = "localised; waiting for " + std::to_string(config_.init_agreeing) +
           " agreeing localisations to initialise";
    return false;
  }
  initialised_ = true;
  T_W_O_ = candidate;
  P_ = measurementCovariance(l, config_);
  init_candidates_.clear();
  rejections_in_a_row_ = 0;
  ++accepted_;
  return true;
}

FusedPose PoseFusion::correct(const Localization& l) {
  if (!have_odometry_) throw InputError("fusion: correct() before any odometry pose");
  if (!l.localized) {
    FusedPose out = current(initialised_ ? FusionStatus::kTracking : FusionStatus::kUninitialised);
    out.note = "not localised: " + l.reason;
    return out;
  }
  if (!l.T_W_C.matrix().allFinite() || !l.covariance.allFinite()) {
    FusedPose out = current(initialised_ ? FusionStatus::kTracking : FusionStatus::kUninitialised);
    out.note = "localisation refused: not finite";
    ++rejected_;
    return out;
  }
  if (!initialised_) {
    std::string note;
    if (!tryInitialise(l, note)) {
      FusedPose out = current(FusionStatus::kUninitialised);
      out.note = note;
      return out;
    }
    FusedPose out = current(FusionStatus::kCorrected);
    out.note = "initialised";
    return out;
  }
  const Eigen::Isometry3d predicted = T_W_O_ * T_O_C_;
  Eigen::Matrix<double, 6, 1> innovation;
  innovation.head<3>() = l.T_W_C.translation() - predicted.translation();
  innovation.tail<3>() = logRotation(l.T_W_C.linear() * predicted.linear().transpose());
  const Matrix6d R = measurementCovariance(l, config_);
  const Matrix6d S = P_ + R;
  const Eigen::LDLT<Matrix6d> S_ldlt(S);
  const double mahalanobis2 = innovation.dot(S_ldlt.solve(innovation));
  if (!(mahalanobis2 <= config_.gate_chi2)) {
    ++rejected_;
    if (++rejections_in_a_row_ >= config_.reset_after_rejections) {
      // The correction itself is what disagrees with everything the map says: start again.
      reset();
      FusedPose out = current(FusionStatus::kUninitialised);
      out.note = "reset after " + std::to_string(config_.reset_after_rejections) +
                 " rejected localisations in a row";
      return out;
    }
    FusedPose out = current(FusionStatus::kTracking);
    out.note = "localisation rejected: " + std::to_string(innovation.head<3>().norm()) +
               " m from the fused pose (Mahalanobis^2 " + std::to_string(mahalanobis2) + ")";
    return out;
  }
  rejections_in_a_row_ = 0;
  const Matrix6d K = S_ldlt.solve(P_).transpose();  // P S^-1 (both symmetric)
  const Eigen::Matrix<double, 6, 1> delta = K * innovation;
  T_W_O_ = perturbation(delta, predicted.translation()) * T_W_O_;
  const Matrix6d I_K = Matrix6d::Identity() - K;
  P_ = I_K * P_ * I_K.transpose() + K * R * K.transpose();
  P_ = 0.5 * (P_ + P_.transpose());
  ++accepted_;
  FusedPose out = current(FusionStatus::kCorrected);
  out.jump_m = delta.head<3>().norm();
  return out;
}

}  // namespace strata::localize
