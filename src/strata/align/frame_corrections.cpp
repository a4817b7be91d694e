// Every frame's pose from its keyframes' optimised poses, and the loop information clamp.
#include <Eigen/Eigenvalues>
#include <algorithm>

#include "strata/align/internal/alignment_steps.h"
#include "strata/core/pose_interpolation.h"

namespace strata::align::detail {

std::vector<Eigen::Isometry3d> correctFrames(const std::vector<double>& frame_timestamps_s,
                                             const std::vector<Eigen::Isometry3d>& frame_T_S_C,
                                             const std::vector<std::size_t>& keyframes,
                                             const std::vector<Eigen::Isometry3d>& keyframe_T_W_C) {
  // Correction per keyframe: the world-from-session transform its optimised pose implies.
  std::vector<Eigen::Isometry3d> T_W_S(keyframes.size());
  for (std::size_t k = 0; k < keyframes.size(); ++k)
    T_W_S[k] = keyframe_T_W_C[k] * frame_T_S_C[keyframes[k]].inverse();
  std::vector<Eigen::Isometry3d> out(frame_T_S_C.size());
  std::size_t k = 0;  // last keyframe at or before frame i
  for (std::size_t i = 0; i < frame_T_S_C.size(); ++i) {
    while (k + 1 < keyframes.size() && keyframes[k + 1] <= i) ++k;
    Eigen::Isometry3d correction = T_W_S[k];
    if (i > keyframes[k] && k + 1 < keyframes.size()) {
      const double t0 = frame_timestamps_s[keyframes[k]];
      const double t1 = frame_timestamps_s[keyframes[k + 1]];
      const double s = t1 > t0 ? (frame_timestamps_s[i] - t0) / (t1 - t0) : 0.0;
      correction = interpolatePose(T_W_S[k], T_W_S[k + 1], std::clamp(s, 0.0, 1.0));
    }
    out[i] = correction * frame_T_S_C[i];
  }
  return out;
}

store::Matrix6d clampInformation(const store::Matrix6d& information, double max_eigenvalue) {
  const store::Matrix6d symmetric = 0.5 * (information + information.transpose());
  Eigen::SelfAdjointEigenSolver<store::Matrix6d> eigen(symmetric);
  const Eigen::Matrix<double, 6, 1> clamped =
      eigen.eigenvalues().cwiseMax(1.0).cwiseMin(max_eigenvalue);
  return eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace strata::align::detail
