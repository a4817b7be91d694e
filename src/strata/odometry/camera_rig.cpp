#include "strata/odometry/camera_rig.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

void validateIntrinsics(const PinholeIntrinsics& k, const std::string& name) {
  if (!(k.fx_px > 0.0) || !(k.fy_px > 0.0) || !std::isfinite(k.fx_px) || !std::isfinite(k.fy_px) ||
      !std::isfinite(k.cx_px) || !std::isfinite(k.cy_px)) {
    throw InputError("CameraRig: " + name + " focal lengths must be positive and finite");
  }
  if (k.width_px <= 0 || k.height_px <= 0) {
    throw InputError("CameraRig: " + name + " image size must be positive");
  }
}

void validateRigid(const Eigen::Isometry3d& T, const std::string& name) {
  const Eigen::Matrix3d R = T.linear();
  if (!T.matrix().allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
      R.determinant() < 0.0) {
    throw InputError("CameraRig: " + name + " must be a finite rigid transform");
  }
}

}  // namespace

void CameraRig::validate() const {
  validateIntrinsics(left, "left");
  validateRigid(T_B_Cl, "T_B_Cl");
  if (right) {
    validateIntrinsics(*right, "right");
    validateRigid(T_B_Cr, "T_B_Cr");
    if ((T_B_Cr.translation() - T_B_Cl.translation()).norm() < 1e-4) {
      throw InputError("CameraRig: stereo baseline (T_B_Cr vs T_B_Cl) must be at least 0.1 mm");
    }
  }
}

}  // namespace strata::odometry
