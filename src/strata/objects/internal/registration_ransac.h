#pragma once
// RANSAC over feature correspondences for registerSurfaces() (internal): hypotheses from
// `ransac_samples` correspondences (least-squares rigid fit, Umeyama 1991), refused early when
// the sample's edges disagree in length (edge_similarity) or the fit tilts the vertical by more
// than max_tilt_deg; scored by the correspondences within the inlier distance; the best distinct
// ones returned, each refitted to its inliers. Deterministic for config.seed (own std::mt19937).
// Thread safety: free functions, no shared state.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "strata/objects/object_registration.h"

namespace strata::objects {

struct Correspondence {
  int source = 0;  // index into the source points
  int target = 0;  // index into the target points
};

struct Hypothesis {
  Eigen::Matrix4f T = Eigen::Matrix4f::Identity();  // source -> target
  int inliers = 0;                                  // correspondences within the inlier distance
};

/// Angle (deg) between the vertical and its image under T's rotation.
double tiltDeg(const Eigen::Matrix4f& T);

/// At most `keep` hypotheses, most inliers first; two hypotheses closer than 10 deg and two
/// voxels count as one. Empty when no sample passed the checks.
std::vector<Hypothesis> ransacUpright(const std::vector<Eigen::Vector3f>& source,
                                      const std::vector<Eigen::Vector3f>& target,
                                      const std::vector<Correspondence>& matches,
                                      const RegistrationConfig& config, std::size_t keep);

/// As ransacUpright for objects that stand upright (config.four_dof): each hypothesis is a
/// rotation about z and a translation fixed by 2 correspondences, refused early when their
/// vertical shifts or horizontal distances disagree by more than the inlier distance (or the
/// distance is under two inlier distances); refitted to its inliers in the same 4 DoF. Far more
/// hypotheses per millisecond than 3-point 6-DoF samples, nearly all of which tilt.
std::vector<Hypothesis> ransacYaw(const std::vector<Eigen::Vector3f>& source,
                                  const std::vector<Eigen::Vector3f>& target,
                                  const std::vector<Correspondence>& matches,
                                  const RegistrationConfig& config, std::size_t keep);

}  // namespace strata::objects
