#include <cmath>

#include "strata/map/camera_math.h"
#include "strata/track/normal_equations.h"

namespace strata {
namespace {

/// The float camera geometry of one evaluation, as track_normal_equations.comp receives it.
struct Geometry {
  Eigen::Matrix3f R_M_C;
  Eigen::Vector3f t_M_C;
  Eigen::Matrix3f R_M_W;
  Eigen::Vector4f K;  // model fx, fy, cx, cy
};

/// One pixel's terms (Eq. in normal_equations.h): false when it is not an inlier.
bool pixelTerms(const Eigen::Vector4f& p4, const Eigen::Vector4f& n4, const ModelView& model,
                const Geometry& g, const AssociationGates& gates, float terms[29]) {
  if (p4.w() < 0.5f || n4.w() < 0.5f) return false;
  const Eigen::Vector3f p_C = p4.head<3>();
  const Eigen::Vector3f p_M = g.R_M_C * p_C + g.t_M_C;
  if (!(p_M.z() > 0.0f)) return false;
  const float u = g.K[0] * p_M.x() / p_M.z() + g.K[2];
  const float v = g.K[1] * p_M.y() / p_M.z() + g.K[3];
  const float fu = std::floor(u + 0.5f);
  const float fv = std::floor(v + 0.5f);
  if (!(fu >= 0.0f && fv >= 0.0f && fu < static_cast<float>(model.intrinsics.width_px) &&
        fv < static_cast<float>(model.intrinsics.height_px))) {
    return false;
  }
  const std::size_t index =
      static_cast<std::size_t>(fv) * model.intrinsics.width_px + static_cast<std::size_t>(fu);
  const float z_M = (*model.depth_m)[index];
  if ((*model.hit)[index] == 0 || !(z_M > 0.0f)) return false;
  const Eigen::Vector3f v_M = pixelRay(fu, fv, g.K) * z_M;
  const Eigen::Vector3f n_M = g.R_M_W * (*model.normal_W)[index];
  const Eigen::Vector3f diff = p_M - v_M;
  if (diff.dot(diff) > gates.max_distance_m * gates.max_distance_m) return false;
  const Eigen::Vector3f live_n_M = g.R_M_C * n4.head<3>();
  if (n_M.dot(live_n_M) < gates.min_normal_cos) return false;
  const float r = n_M.dot(diff);
  const Eigen::Vector3f n_C = g.R_M_C.transpose() * n_M;
  const Eigen::Vector3f pxn = p_C.cross(n_C);
  const float J[6] = {n_C.x(), n_C.y(), n_C.z(), pxn.x(), pxn.y(), pxn.z()};
  const float abs_r = std::abs(r);
  const float w = gates.huber_m > 0.0f && abs_r > gates.huber_m ? gates.huber_m / abs_r : 1.0f;
  int k = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) terms[k++] = w * J[i] * J[j];
  }
  for (int i = 0; i < 6; ++i) terms[21 + i] = w * J[i] * r;
  terms[27] = r * r;
  terms[28] = 1.0f;
  return true;
}

}  // namespace

NormalEquations normalEquationsReference(const LiveView& live, const ModelView& model,
                                         const Eigen::Isometry3d& T_W_C,
                                         const AssociationGates& gates) {
  const Eigen::Isometry3d T_M_W = model.T_W_M.inverse();
  const Eigen::Matrix4f T_M_C = (T_M_W * T_W_C).matrix().cast<float>();
  Geometry g;
  g.R_M_C = T_M_C.topLeftCorner<3, 3>();
  g.t_M_C = T_M_C.topRightCorner<3, 1>();
  g.R_M_W = T_M_W.rotation().cast<float>();
  g.K = Eigen::Vector4f(model.intrinsics.fx_px, model.intrinsics.fy_px, model.intrinsics.cx_px,
                        model.intrinsics.cy_px);
  NormalEquations sums;
  const std::size_t pixels = static_cast<std::size_t>(live.width_px) * live.height_px;
  float terms[29];
  for (std::size_t i = 0; i < pixels; ++i) {
    if (!pixelTerms((*live.vertex_C)[i], (*live.normal_C)[i], model, g, gates, terms)) continue;
    for (int k = 0; k < 21; ++k) sums.JtJ[k] += terms[k];
    for (int k = 0; k < 6; ++k) sums.Jtr[k] += terms[21 + k];
    sums.residual_sq += terms[27];
    ++sums.inliers;
  }
  return sums;
}

}  // namespace strata
