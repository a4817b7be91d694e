#include "strata/align/loop_verifier.h"

#include <algorithm>
#include <cmath>
#include <Eigen/Eigenvalues>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <sstream>
#include <vector>

#include "strata/align/internal/dense_icp.h"
#include "strata/align/internal/descriptor_matching.h"
#include "strata/align/internal/surface_registration.h"
#include "strata/core/error.h"

namespace strata::align {
namespace {

// Below this squared ICP residual the information would grow without bound on perfect data.
constexpr double kMinResidualSquared = 1e-6;
constexpr double kRansacConfidence = 0.999;

std::string describe(const char* what, double value, const char* relation, double gate) {
  std::ostringstream text;
  text << what << ' ' << value << ' ' << relation << ' ' << gate;
  return text.str();
}

void checkKeyframe(const VerifyKeyframe& k, const char* name) {
  const std::string which = std::string("verifyLoop: keyframe ") + name;
  if (k.features == nullptr) throw InputError(which + " has no features");
  if (k.depth == nullptr || k.depth->empty()) throw InputError(which + " has no depth image");
  k.intrinsics.validate();
  if (k.depth->width_px != k.intrinsics.width_px || k.depth->height_px != k.intrinsics.height_px) {
    throw InputError(which + ": depth image " + std::to_string(k.depth->width_px) + "x" +
                     std::to_string(k.depth->height_px) + " does not match its intrinsics");
  }
  const KeyframeFeatures& f = *k.features;
  if (f.descriptors.size() != f.size() || f.points_C_m.size() != f.size()) {
    throw InputError(which + ": " + std::to_string(f.size()) + " keypoints, " +
                     std::to_string(f.descriptors.size()) + " descriptors and " +
                     std::to_string(f.points_C_m.size()) + " points");
  }
}

// Matches whose b feature has a 3D point: b's points (camera b) and a's pixels.
struct Correspondences {
  std::vector<cv::Point3f> points_b;
  std::vector<cv::Point2f> pixels_a;
  std::vector<int> index_a;  // a's feature of each
};

Correspondences correspondences(const KeyframeFeatures& a, const KeyframeFeatures& b,
                                const VerifyConfig& config) {
  Correspondences c;
  for (const auto& [i, j] : detail::matchDescriptors(
           a.descriptors, b.descriptors, config.ratio_test, config.max_hamming_distance)) {
    const Eigen::Vector3f& p = b.points_C_m[static_cast<std::size_t>(j)];
    if (!p.allFinite()) continue;
    const Eigen::Vector2f& uv = a.keypoints_px[static_cast<std::size_t>(i)];
    c.points_b.emplace_back(p.x(), p.y(), p.z());
    c.pixels_a.emplace_back(uv.x(), uv.y());
    c.index_a.push_back(i);
  }
  return c;
}

cv::Mat cameraMatrix(const CameraIntrinsics& k) {
  return (cv::Mat_<double>(3, 3) << k.fx_px, 0.0, k.cx_px, 0.0, k.fy_px, k.cy_px, 0.0, 0.0, 1.0);
}

Eigen::Isometry3d poseOf(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R_cv;
  cv::Rodrigues(rvec, R_cv);
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  cv::cv2eigen(R_cv, R);
  cv::cv2eigen(tvec, t);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

// PnP RANSAC of b's points into a's image, refined on the inliers; false when RANSAC fails.
bool solvePnp(const Correspondences& c, const CameraIntrinsics& intrinsics_a,
              const VerifyConfig& config, Eigen::Isometry3d& T_a_b, std::vector<int>& inliers) {
  const cv::Mat K = cameraMatrix(intrinsics_a);
  cv::Mat rvec, tvec;
  try {
    if (!cv::solvePnPRansac(c.points_b, c.pixels_a, K, cv::noArray(), rvec, tvec, false,
                            config.pnp_iterations, static_cast<float>(config.pnp_reprojection_px),
                            kRansacConfidence, inliers, cv::SOLVEPNP_EPNP)) {
      return false;
    }
    if (inliers.size() < 6) return false;
    std::vector<cv::Point3f> points_in;
    std::vector<cv::Point2f> pixels_in;
    for (const int i : inliers) {
      points_in.push_back(c.points_b[static_cast<std::size_t>(i)]);
      pixels_in.push_back(c.pixels_a[static_cast<std::size_t>(i)]);
    }
    cv::solvePnP(points_in, pixels_in, K, cv::noArray(), rvec, tvec, true, cv::SOLVEPNP_ITERATIVE);
  } catch (const cv::Exception&) {
    // Degenerate configurations (collinear points, a singular system) are unlucky data.
    return false;
  }
  T_a_b = poseOf(rvec, tvec);
  return T_a_b.matrix().allFinite();
}

// RMS of |p_a - T_a_b p_b| over the PnP inliers where a's feature has a 3D point too.
double pnpResidual(const Correspondences& c, const std::vector<int>& inliers,
                   const KeyframeFeatures& a, const Eigen::Isometry3d& T_a_b) {
  double sum = 0.0;
  int n = 0;
  for (const int i : inliers) {
    const Eigen::Vector3f& p_a = a.points_C_m[static_cast<std::size_t>(c.index_a[i])];
    if (!p_a.allFinite()) continue;
    const cv::Point3f& p = c.points_b[static_cast<std::size_t>(i)];
    sum += (p_a.cast<double>() - T_a_b * Eigen::Vector3d(p.x, p.y, p.z)).squaredNorm();
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

// Smallest eigenvalue of the mean n n^T over the ICP's correspondences: the translational block
// of the unweighted J^T J is the sum of n n^T (J's translation part is R^T n, a unit vector).
double translationConstraint(const store::Matrix6d& JtJ, int count) {
  if (count <= 0) return 0.0;
  const Eigen::Matrix3d N = JtJ.topLeftCorner<3, 3>() / count;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(N, Eigen::EigenvaluesOnly).eigenvalues()(0);
}

// The ICP step and its gates; fills the measurement's pose, residual, overlap and information.
// `first_gate_m`: the ICP's first association gate; `max_correction_m`: how far ICP may move the
// initial pose; `min_constraint` > 0 refuses ICP that leaves a translation unconstrained.
void refineWithIcp(const VerifyKeyframe& a, const VerifyKeyframe& b, const VerifyConfig& config,
                   double first_gate_m, double max_correction_m, double min_constraint,
                   LoopMeasurement& m) {
  const detail::DenseIcpConfig icp{config.icp_iterations, config.icp_stride_px, first_gate_m,
                                   config.icp_max_normal_angle_rad};
  const detail::DenseIcpResult r =
      detail::denseIcp(*a.depth, a.intrinsics, *b.depth, b.intrinsics, m.T_a_b, icp);
  if (!r.converged) {
    m.reason = "ICP found too few correspondences between the depth images";
    return;
  }
  if (!std::isfinite(r.rms_m) || !r.JtJ.allFinite() || !r.T_a_b.matrix().allFinite()) {
    m.reason = "ICP diverged (a non-finite pose or residual)";
    return;
  }
  const double correction_m = (r.T_a_b.translation() - m.T_a_b.translation()).norm();
  m.T_a_b = r.T_a_b;
  m.residual_m = r.rms_m;
  m.overlap = r.valid_b > 0 ? static_cast<double>(r.inliers) / r.valid_b : 0.0;
  m.information = r.JtJ / std::max(r.rms_m * r.rms_m, kMinResidualSquared);
  const double constraint = translationConstraint(r.JtJ, r.inliers);
  if (correction_m > max_correction_m) {
    m.reason = describe("ICP moved the initial pose by", correction_m, "m, over", max_correction_m);
  } else if (min_constraint > 0.0 && constraint < min_constraint) {
    m.reason = describe("ICP's surfaces constrain a translation by", constraint, "below",
                        min_constraint);
  } else if (m.residual_m > config.max_icp_rms_m) {
    m.reason = describe("ICP residual", m.residual_m, "m, over", config.max_icp_rms_m);
  } else if (m.overlap < config.min_icp_overlap) {
    m.reason = describe("ICP overlap", m.overlap, "below", config.min_icp_overlap);
  } else {
    m.accepted = true;
  }
}

}  // namespace

void VerifyConfig::validate() const {
  if (!(ratio_test > 0.0f && ratio_test <= 1.0f)) {
    throw InputError("VerifyConfig: ratio_test must be in (0, 1]");
  }
  if (max_hamming_distance < 0 || max_hamming_distance > 256) {
    throw InputError("VerifyConfig: max_hamming_distance must be in [0, 256]");
  }
  if (!(pnp_reprojection_px > 0.0))
    throw InputError("VerifyConfig: pnp_reprojection_px must be > 0");
  if (pnp_iterations < 1) throw InputError("VerifyConfig: pnp_iterations must be >= 1");
  if (min_inliers < 6) throw InputError("VerifyConfig: min_inliers must be >= 6");
  if (!(min_inlier_ratio >= 0.0 && min_inlier_ratio <= 1.0)) {
    throw InputError("VerifyConfig: min_inlier_ratio must be in [0, 1]");
  }
  if (icp_iterations < 1) throw InputError("VerifyConfig: icp_iterations must be >= 1");
  if (icp_stride_px < 1) throw InputError("VerifyConfig: icp_stride_px must be >= 1");
  if (!(icp_max_distance_m > 0.0)) throw InputError("VerifyConfig: icp_max_distance_m must be > 0");
  if (!(icp_max_normal_angle_rad > 0.0)) {
    throw InputError("VerifyConfig: icp_max_normal_angle_rad must be > 0");
  }
  if (!(max_icp_rms_m > 0.0)) throw InputError("VerifyConfig: max_icp_rms_m must be > 0");
  if (!(min_icp_overlap >= 0.0 && min_icp_overlap <= 1.0)) {
    throw InputError("VerifyConfig: min_icp_overlap must be in [0, 1]");
  }
  if (!(max_icp_correction_m > 0.0)) {
    throw InputError("VerifyConfig: max_icp_correction_m must be > 0");
  }
  if (surface_ransac_iterations < 1)
    throw InputError("VerifyConfig: surface_ransac_iterations must be >= 1");
  if (!(surface_inlier_m > 0.0)) throw InputError("VerifyConfig: surface_inlier_m must be > 0");
  if (min_surface_inliers < 3) throw InputError("VerifyConfig: min_surface_inliers must be >= 3");
  if (!(surface_icp_max_distance_m > 0.0))
    throw InputError("VerifyConfig: surface_icp_max_distance_m must be > 0");
  if (!(surface_max_icp_correction_m > 0.0))
    throw InputError("VerifyConfig: surface_max_icp_correction_m must be > 0");
  if (!(min_surface_constraint >= 0.0 && min_surface_constraint <= 1.0 / 3.0))
    throw InputError("VerifyConfig: min_surface_constraint must be in [0, 1/3]");
}

namespace {

LoopMeasurement verifyByAppearance(const VerifyKeyframe& a, const VerifyKeyframe& b,
                                   const VerifyConfig& config) {
  LoopMeasurement m;
  const Correspondences c = correspondences(*a.features, *b.features, config);
  m.matches = static_cast<int>(c.points_b.size());
  if (m.matches < config.min_inliers) {
    m.reason =
        describe("too few descriptor matches with depth:", m.matches, "below", config.min_inliers);
    return m;
  }
  std::vector<int> inliers;
  if (!solvePnp(c, a.intrinsics, config, m.T_a_b, inliers)) {
    m.reason = "PnP RANSAC found no pose";
    return m;
  }
  m.inliers = static_cast<int>(inliers.size());
  m.inlier_ratio = static_cast<double>(m.inliers) / m.matches;
  m.residual_m = pnpResidual(c, inliers, *a.features, m.T_a_b);
  if (m.inliers < config.min_inliers) {
    m.reason = describe("too few PnP inliers:", m.inliers, "below", config.min_inliers);
  } else if (m.inlier_ratio < config.min_inlier_ratio) {
    m.reason = describe("PnP inlier ratio", m.inlier_ratio, "below", config.min_inlier_ratio);
  } else {
    refineWithIcp(a, b, config, config.icp_max_distance_m, config.max_icp_correction_m, 0.0, m);
  }
  return m;
}

LoopMeasurement verifyBySurface(const VerifyKeyframe& a, const VerifyKeyframe& b,
                                const VerifyConfig& config) {
  LoopMeasurement m;
  m.from_surface = true;
  const detail::SurfaceRegistration r = detail::registerSurfaces(
      *a.surface, *b.surface,
      {config.surface_ransac_iterations, config.surface_inlier_m, 0.9, 0.15});
  m.matches = r.correspondences;
  m.inliers = r.inliers;
  m.inlier_ratio = r.correspondences > 0 ? static_cast<double>(r.inliers) / r.correspondences : 0.0;
  if (!r.found || r.inliers < config.min_surface_inliers) {
    m.reason = describe("too few FPFH RANSAC inliers:", r.inliers, "below",
                        config.min_surface_inliers);
    return m;
  }
  m.T_a_b = r.T_a_b;
  refineWithIcp(a, b, config, config.surface_icp_max_distance_m,
                config.surface_max_icp_correction_m, config.min_surface_constraint, m);
  return m;
}

}  // namespace

LoopMeasurement verifyLoop(const VerifyKeyframe& a, const VerifyKeyframe& b,
                           const VerifyConfig& config) {
  config.validate();
  checkKeyframe(a, "a");
  checkKeyframe(b, "b");
  LoopMeasurement m = verifyByAppearance(a, b, config);
  if (m.accepted || a.surface == nullptr || b.surface == nullptr) return m;
  LoopMeasurement s = verifyBySurface(a, b, config);
  if (!s.accepted) s.reason = "appearance: " + m.reason + "; surface: " + s.reason;
  return s;
}

}  // namespace strata::align
