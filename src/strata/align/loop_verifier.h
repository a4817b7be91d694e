#pragma once
// Geometric verification of a loop-closure candidate between two keyframes a and b: ORB matches
// (mutual nearest, ratio test), 3D-2D PnP RANSAC (OpenCV) of b's points into a's image, then
// dense point-to-plane ICP of b's depth against a's (projective association) from the PnP pose.
// When that fails and both keyframes carry a surface description (surface_descriptor.h), the
// surface path runs instead: FPFH correspondences and RANSAC give the initial pose, the same
// dense ICP and gates refine it, and ICP whose normals leave a translation unconstrained (a wall
// and a floor alone) is refused.
// The result is the relative pose T_a_b (camera b in camera a's frame: T_X_a^-1 * T_X_b), with
// the figures that decide acceptance. Thread safety: free function, no shared state.
#include <Eigen/Geometry>
#include <string>

#include "strata/align/keyframe_features.h"
#include "strata/align/surface_descriptor.h"
#include "strata/core/types.h"
#include "strata/store/store_types.h"

namespace strata::align {

struct VerifyConfig {
  float ratio_test = 0.8f;           // best / second-best Hamming distance
  int max_hamming_distance = 64;
  double pnp_reprojection_px = 3.0;  // RANSAC inlier threshold
  int pnp_iterations = 200;
  int min_inliers = 25;              // PnP inliers to accept
  double min_inlier_ratio = 0.3;     // PnP inliers / matches with a 3D point
  int icp_iterations = 15;
  int icp_stride_px = 4;             // ICP uses every n-th pixel in u and v
  double icp_max_distance_m = 0.10;  // association gate
  double icp_max_normal_angle_rad = 0.5;
  double max_icp_rms_m = 0.02;       // point-to-plane RMS of the ICP inliers to accept
  double min_icp_overlap = 0.3;      // ICP inliers / valid subsampled pixels of b
  double max_icp_correction_m = 0.15;  // ICP moving the PnP pose farther than this rejects
  // The surface path (both keyframes with a surface description, the ORB path failed):
  int surface_ransac_iterations = 4000;  // RANSAC triples of FPFH correspondences
  double surface_inlier_m = 0.08;        // keypoint distance of a RANSAC inlier
  int min_surface_inliers = 10;          // RANSAC inliers to go on to ICP
  double surface_icp_max_distance_m = 0.2;     // ICP's first gate (RANSAC's pose is coarser)
  double surface_max_icp_correction_m = 0.3;   // ICP moving the RANSAC pose farther rejects
  /// Smallest eigenvalue of the mean n n^T over the ICP's correspondences (n: a's unit normals;
  /// 1/3 for three orthogonal planes seen alike, 0 when a direction is unconstrained).
  double min_surface_constraint = 0.03;
  void validate() const;
};

/// One keyframe as the verifier sees it.
struct VerifyKeyframe {
  const KeyframeFeatures* features = nullptr;
  const DepthImage* depth = nullptr;
  CameraIntrinsics intrinsics;
  const KeyframeSurface* surface = nullptr;  // optional: enables the surface path
};

struct LoopMeasurement {
  bool accepted = false;
  bool from_surface = false;          // the surface path measured it (matches, inliers: FPFH)
  std::string reason;                 // why it was rejected ("" when accepted)
  Eigen::Isometry3d T_a_b = Eigen::Isometry3d::Identity();
  int matches = 0;                    // descriptor matches with a 3D point in b
  int inliers = 0;                    // PnP inliers
  double inlier_ratio = 0.0;          // inliers / matches
  double residual_m = 0.0;            // ICP point-to-plane RMS (m); PnP-only: 3D residual
  double overlap = 0.0;               // ICP inliers / valid subsampled pixels of b
  store::Matrix6d information = store::Matrix6d::Identity();  // (t, r) order as in the store
};

/// Verifies that b shows the place a shows and measures T_a_b. Never throws for unlucky data
/// (too few matches, RANSAC failure, ICP divergence: accepted = false with the reason);
/// InputError when a keyframe lacks features or depth.
LoopMeasurement verifyLoop(const VerifyKeyframe& a, const VerifyKeyframe& b,
                           const VerifyConfig& config = {});

}  // namespace strata::align
