#include "strata/odometry/frontend/camera.h"

#include <cmath>
#include <sstream>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

constexpr int kMaxNewtonIterations = 30;

// Distorted normalized coordinates of the radial-tangential model and their Jacobian.
Eigen::Vector2d distortRadTan(const std::array<double, 4>& c, const Eigen::Vector2d& p,
                              Eigen::Matrix2d* jacobian) {
  const double k1 = c[0], k2 = c[1], p1 = c[2], p2 = c[3];
  const double x = p.x(), y = p.y(), r2 = x * x + y * y;
  const double radial = 1.0 + k1 * r2 + k2 * r2 * r2;
  const Eigen::Vector2d d(x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
                          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y);
  if (jacobian) {
    const double dr_dx = 2.0 * x * (k1 + 2.0 * k2 * r2), dr_dy = 2.0 * y * (k1 + 2.0 * k2 * r2);
    *jacobian << radial + x * dr_dx + 2.0 * p1 * y + 6.0 * p2 * x,
        x * dr_dy + 2.0 * p1 * x + 2.0 * p2 * y, y * dr_dx + 2.0 * p1 * x + 2.0 * p2 * y,
        radial + y * dr_dy + 6.0 * p1 * y + 2.0 * p2 * x;
  }
  return d;
}

// theta_d(theta) of the equidistant model and its derivative.
double equidistantTheta(const std::array<double, 4>& c, double theta, double* derivative) {
  const double t2 = theta * theta;
  const double poly = 1.0 + t2 * (c[0] + t2 * (c[1] + t2 * (c[2] + t2 * c[3])));
  if (derivative) {
    *derivative = 1.0 + t2 * (3.0 * c[0] + t2 * (5.0 * c[1] + t2 * (7.0 * c[2] + t2 * 9.0 * c[3])));
  }
  return theta * poly;
}

Eigen::Vector2d distortEquidistant(const std::array<double, 4>& c, const Eigen::Vector2d& p) {
  const double r = p.norm();
  if (r < 1e-12) return p;
  return p * (equidistantTheta(c, std::atan(r), nullptr) / r);
}

Eigen::Vector2d undistortRadTan(const std::array<double, 4>& c, const Eigen::Vector2d& d) {
  Eigen::Vector2d p = d;
  for (int i = 0; i < kMaxNewtonIterations; ++i) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d residual = distortRadTan(c, p, &J) - d;
    const Eigen::Vector2d step = J.partialPivLu().solve(residual);
    p -= step;
    if (step.squaredNorm() < 1e-26) break;
  }
  return p;
}

Eigen::Vector2d undistortEquidistant(const std::array<double, 4>& c, const Eigen::Vector2d& d) {
  const double rd = d.norm();
  if (rd < 1e-12) return d;
  double theta = rd;
  for (int i = 0; i < kMaxNewtonIterations; ++i) {
    double derivative = 1.0;
    const double step = (equidistantTheta(c, theta, &derivative) - rd) / derivative;
    theta -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return d * (std::tan(theta) / rd);
}

}  // namespace

Camera Camera::fromIntrinsics(const CameraIntrinsics& intrinsics, const std::string& name) {
  Camera camera;
  camera.width_px = intrinsics.width_px;
  camera.height_px = intrinsics.height_px;
  camera.fx_px = intrinsics.fx_px;
  camera.fy_px = intrinsics.fy_px;
  camera.cx_px = intrinsics.cx_px;
  camera.cy_px = intrinsics.cy_px;
  camera.name = name;
  return camera;
}

void Camera::validate() const {
  const auto fail = [&](const std::string& what) { throw InputError(name + ": " + what); };
  if (width_px <= 0 || height_px <= 0) fail("image size must be positive");
  if (!(fx_px > 0.0 && fy_px > 0.0 && std::isfinite(fx_px) && std::isfinite(fy_px))) {
    fail("focal lengths fx_px, fy_px must be finite and positive");
  }
  if (!std::isfinite(cx_px) || !std::isfinite(cy_px)) fail("principal point must be finite");
  for (double k : coefficients) {
    if (!std::isfinite(k)) fail("distortion coefficients must be finite");
  }
  const Eigen::Matrix3d R = T_B_C.linear();
  if (!T_B_C.matrix().allFinite() ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0.0) {
    fail("T_B_C rotation is not a rotation matrix (orthonormal, det +1 within 1e-6)");
  }
}

Eigen::Vector2d Camera::project(const Eigen::Vector2d& xy_norm) const {
  Eigen::Vector2d d = xy_norm;
  if (distortion == DistortionModel::kRadialTangential) {
    d = distortRadTan(coefficients, xy_norm, nullptr);
  } else if (distortion == DistortionModel::kEquidistant) {
    d = distortEquidistant(coefficients, xy_norm);
  }
  return {fx_px * d.x() + cx_px, fy_px * d.y() + cy_px};
}

Eigen::Vector2d Camera::projectPoint(const Eigen::Vector3d& p_C) const {
  return project(p_C.head<2>() / p_C.z());
}

Eigen::Vector2d Camera::undistort(const Eigen::Vector2d& uv_px) const {
  const Eigen::Vector2d d((uv_px.x() - cx_px) / fx_px, (uv_px.y() - cy_px) / fy_px);
  if (distortion == DistortionModel::kRadialTangential) return undistortRadTan(coefficients, d);
  if (distortion == DistortionModel::kEquidistant) return undistortEquidistant(coefficients, d);
  return d;
}

bool Camera::contains(const Eigen::Vector2d& uv_px, double border_px) const {
  return uv_px.x() >= border_px && uv_px.y() >= border_px &&
         uv_px.x() <= width_px - 1 - border_px && uv_px.y() <= height_px - 1 - border_px;
}

Eigen::Matrix3d StereoCamera::essentialRightLeft() const {
  // x_R = R_C1_C0 x_L + t_C1_C0 (up to depth): E = [t]x R.
  const Eigen::Isometry3d T_C1_C0 = T_C0_C1().inverse();
  const Eigen::Vector3d t = T_C1_C0.translation();
  Eigen::Matrix3d t_cross;
  t_cross << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  return t_cross * T_C1_C0.linear();
}

void StereoCamera::validate() const {
  left.validate();
  right.validate();
  if (!(baseline_m() > 1e-3)) {
    std::ostringstream msg;
    msg << left.name << "/" << right.name << ": stereo baseline " << baseline_m()
        << " m from the two T_B_C must exceed 1 mm";
    throw InputError(msg.str());
  }
}

}  // namespace strata::odometry
