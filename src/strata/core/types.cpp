#include "strata/core/types.h"

#include <cmath>
#include <sstream>

#include "strata/core/error.h"

namespace strata {

void CameraIntrinsics::validate() const {
  std::ostringstream problem;
  if (width_px <= 0 || height_px <= 0) {
    problem << "image size " << width_px << "x" << height_px << " must be positive";
  } else if (!std::isfinite(fx_px) || !std::isfinite(fy_px) || fx_px <= 0.0f || fy_px <= 0.0f) {
    problem << "focal lengths fx=" << fx_px << " fy=" << fy_px << " must be finite and positive";
  } else if (!std::isfinite(cx_px) || !std::isfinite(cy_px)) {
    problem << "principal point cx=" << cx_px << " cy=" << cy_px << " must be finite";
  }
  if (!problem.str().empty()) throw InputError("invalid camera intrinsics: " + problem.str());
}

void validatePose(const Eigen::Isometry3d& T_W_C, const std::string& what) {
  const Eigen::Matrix4d& m = T_W_C.matrix();
  if (!m.allFinite()) throw InputError(what + ": pose has non-finite entries (NaN or inf)");
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  const double orthonormality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (orthonormality_error > 1e-3 || R.determinant() < 0.0) {
    std::ostringstream msg;
    msg << what << ": pose rotation is not a rotation (|R^T R - I| = " << orthonormality_error
        << ", det = " << R.determinant() << ")";
    throw InputError(msg.str());
  }
}

void validateFrame(const RgbdFrame& frame, const CameraIntrinsics& intrinsics) {
  const std::string what = "frame '" + frame.name + "'";
  if (frame.depth.empty()) throw InputError(what + ": depth image is empty");
  if (frame.depth.width_px != intrinsics.width_px || frame.depth.height_px != intrinsics.height_px) {
    std::ostringstream msg;
    msg << what << ": depth image is " << frame.depth.width_px << "x" << frame.depth.height_px
        << " but the camera intrinsics say " << intrinsics.width_px << "x" << intrinsics.height_px;
    throw InputError(msg.str());
  }
  if (!frame.color.empty() && (frame.color.width_px != frame.depth.width_px ||
                               frame.color.height_px != frame.depth.height_px)) {
    std::ostringstream msg;
    msg << what << ": colour image is " << frame.color.width_px << "x" << frame.color.height_px
        << " but depth is " << frame.depth.width_px << "x" << frame.depth.height_px;
    throw InputError(msg.str());
  }
  validatePose(frame.T_W_C, what);
}

}  // namespace strata
