#include "strata/odometry/frontend/stereo_matcher.h"

#include <Eigen/Dense>
#include <cmath>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

// Distance of the right point to the epipolar line E xy_left, right-image pixels.
double epipolarDistancePx(const Eigen::Matrix3d& E_right_left, const Eigen::Vector2d& xy_left,
                          const Eigen::Vector2d& xy_right, double focal_px) {
  const Eigen::Vector3d line = E_right_left * xy_left.homogeneous();
  const double norm = line.head<2>().norm();
  if (norm < 1e-12) return 0.0;
  return std::abs(xy_right.homogeneous().dot(line)) / norm * focal_px;
}

}  // namespace

void StereoMatchConfig::validate() const {
  if (!(epipolar_max_px > 0.0)) throw InputError("StereoMatchConfig: epipolar_max_px must be > 0");
  if (!(min_depth_m > 0.0 && max_depth_m > min_depth_m)) {
    throw InputError("StereoMatchConfig: need 0 < min_depth_m < max_depth_m");
  }
  if (!(init_depth_m > 0.0)) throw InputError("StereoMatchConfig: init_depth_m must be > 0");
  if (!(retry_depth_m >= 0.0)) throw InputError("StereoMatchConfig: retry_depth_m must be >= 0");
}

std::optional<Eigen::Vector2d> triangulateDepths(const Eigen::Vector2d& xy_left,
                                                 const Eigen::Vector2d& xy_right,
                                                 const Eigen::Isometry3d& T_C1_C0) {
  // z_r f_r = z_l R f_l + t  =>  [R f_l, -f_r] (z_l, z_r)^T = -t.
  Eigen::Matrix<double, 3, 2> A;
  A.col(0) = T_C1_C0.linear() * xy_left.homogeneous();
  A.col(1) = -xy_right.homogeneous();
  const Eigen::Matrix2d normal = A.transpose() * A;
  if (std::abs(normal.determinant()) < 1e-12 * normal.squaredNorm()) return std::nullopt;
  return Eigen::Vector2d(normal.ldlt().solve(-A.transpose() * T_C1_C0.translation()));
}

std::vector<std::optional<StereoMatch>> matchStereo(
    const std::vector<cv::Mat>& pyramid_left, const std::vector<cv::Mat>& pyramid_right,
    const StereoCamera& camera, const std::vector<Eigen::Vector2d>& uv_left_px,
    const std::vector<Eigen::Vector2d>& xy_left_norm,
    const std::vector<std::optional<Eigen::Vector2d>>& guess_right_px,
    const std::vector<bool>& retry_near, const KltConfig& klt, double border_px,
    const StereoMatchConfig& config) {
  const std::size_t n = uv_left_px.size();
  std::vector<std::optional<StereoMatch>> matches(n);
  const Eigen::Isometry3d T_C1_C0 = camera.T_C0_C1().inverse();
  const Eigen::Matrix3d E = camera.essentialRightLeft();
  const cv::Size right_size(camera.right.width_px, camera.right.height_px);
  const auto projectionGuess = [&](std::size_t i, double depth_m) {
    const Eigen::Vector2d guess =
        camera.right.projectPoint(T_C1_C0 * (depth_m * xy_left_norm[i].homogeneous()));
    return guess.allFinite() ? guess : uv_left_px[i];
  };
  // One KLT pass over `subset` from `guesses`; accepted matches fill `matches`.
  const auto attempt = [&](const std::vector<std::size_t>& subset,
                           const std::vector<Eigen::Vector2d>& guesses) {
    std::vector<cv::Point2f> from, to;
    for (std::size_t j = 0; j < subset.size(); ++j) {
      from.emplace_back(static_cast<float>(uv_left_px[subset[j]].x()),
                        static_cast<float>(uv_left_px[subset[j]].y()));
      to.emplace_back(static_cast<float>(guesses[j].x()), static_cast<float>(guesses[j].y()));
    }
    const std::vector<KltStatus> status =
        trackForwardBackward(pyramid_left, pyramid_right, from, &to, right_size, border_px, klt);
    for (std::size_t j = 0; j < subset.size(); ++j) {
      if (status[j] != KltStatus::kOk) continue;
      const std::size_t i = subset[j];
      const Eigen::Vector2d uv_right(to[j].x, to[j].y);
      const Eigen::Vector2d xy_right = camera.right.undistort(uv_right);
      if (epipolarDistancePx(E, xy_left_norm[i], xy_right, camera.right.focalMean()) >
          config.epipolar_max_px) {
        continue;
      }
      const std::optional<Eigen::Vector2d> depths =
          triangulateDepths(xy_left_norm[i], xy_right, T_C1_C0);
      if (!depths || depths->minCoeff() < config.min_depth_m ||
          depths->maxCoeff() > config.max_depth_m) {
        continue;
      }
      matches[i] = StereoMatch{uv_right, xy_right, depths->x()};
    }
  };
  std::vector<std::size_t> all(n);
  std::vector<Eigen::Vector2d> guesses(n);
  for (std::size_t i = 0; i < n; ++i) {
    all[i] = i;
    guesses[i] = guess_right_px[i] ? *guess_right_px[i] : projectionGuess(i, config.init_depth_m);
  }
  attempt(all, guesses);
  // Near points (a floor under the sensor) lie beyond KLT's capture range from a far guess.
  if (config.retry_depth_m > 0.0) {
    std::vector<std::size_t> retry;
    std::vector<Eigen::Vector2d> near_guesses;
    for (std::size_t i = 0; i < n; ++i) {
      if (matches[i] || !retry_near[i]) continue;
      retry.push_back(i);
      near_guesses.push_back(projectionGuess(i, config.retry_depth_m));
    }
    attempt(retry, near_guesses);
  }
  return matches;
}

}  // namespace strata::odometry
