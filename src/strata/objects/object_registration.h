#pragma once
// Registration of an observation's surface onto a model's: global (FPFH descriptors of every
// sample, each paired with its feature_neighbours nearest descriptors, RANSAC over them: yaw +
// translation from 2 pairs (four_dof) or 6 DoF refusing tilted hypotheses) then
// local (point-to-plane ICP, coarse then fine). Deterministic for a seed.
// Built on PCL (Debian libpcl-dev); docs/objects.md says why PCL and which of its classes.
// Everything PCL stays in the .cpp files (and internal/): callers see Eigen, SurfaceCloud and the
// opaque SurfaceFeatures.
// Thread safety: registerSurfaces on plain clouds shares no state (PCL objects are local to the
// call); on SurfaceFeatures, as SurfaceFeatures says.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "strata/objects/object_observation.h"

namespace strata::objects {

struct RegistrationConfig {
  float voxel_size_m = 0.02f;           // of the clouds; radii below are in these voxels
  float feature_radius_voxels = 5.0f;   // FPFH support
  float inlier_distance_voxels = 1.5f;  // RANSAC and fitness inlier bound
  int ransac_iterations = 20000;
  int ransac_samples = 3;
  float edge_similarity = 0.9f;  // polygon rejection of sample sets
  int icp_iterations = 30;
  float icp_max_distance_voxels = 2.0f;
  /// A first ICP stage pairs points this far apart: it pulls a RANSAC hypothesis into the fine
  /// stage's reach along directions few planes of a partial view constrain. Wider costs time.
  float icp_coarse_distance_voxels = 8.0f;
  /// Rotations about the world's vertical only (objects stand on the floor): RANSAC hypotheses
  /// that tilt the object by more than this are refused. 180 disables.
  float max_tilt_deg = 10.0f;
  /// Hypotheses in 4 DoF (yaw about the vertical + translation) from 2 correspondences, for
  /// objects that stand upright (object frames share the world's vertical). false: 6-DoF samples
  /// of ransac_samples correspondences, tilted ones refused.
  bool four_dof = true;
  /// Each source descriptor is paired with this many nearest target descriptors: on partial
  /// views the right target point is often only second or third nearest (1..8).
  int feature_neighbours = 3;
  std::uint32_t seed = 1;  // RANSAC is deterministic for a given seed
  /// Other upright poses kept beside the best (RegistrationResult::alternatives): the other
  /// refined RANSAC hypotheses and the best pose turned a quarter, a half and three quarters
  /// about the source's centre, each refined by ICP, when their fitness reaches
  /// alternative_min_fitness of the best's. A near-square footprint or a symmetric part fits
  /// several yaws almost equally; the caller scores them with more than the point fit (the
  /// object database with its volumetric check). false: none (the best pose alone).
  bool yaw_alternatives = true;
  float alternative_min_fitness = 0.7f;  // (0, 1]
  void validate() const;   // InputError naming the bad field
};

/// An upright pose other than the best, with the same figures as RegistrationResult's.
struct PoseAlternative {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  double fitness = 0.0;
  double target_coverage = 0.0;
  double horizontal_constraint = 0.0;
};

struct RegistrationResult {
  bool converged = false;
  std::string reason;  // "" when converged, else why not
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  double fitness = 0.0;  // share of source points within the inlier distance after ICP
  double rmse_m = 0.0;   // of those inliers
  /// The fitness the other way round: share of target points within the inlier distance of the
  /// registered source (how much of the target the source covers).
  double target_coverage = 0.0;
  /// How firmly the overlap holds the horizontal translation: the smaller eigenvalue of the
  /// mean of n_xy n_xy^T over the target's normals at the inliers (0..0.5; 0.5 for normals spread
  /// evenly around the vertical, 0 for one vertical face or a top seen alone, along which the
  /// source may slide without changing the fit). Point-to-plane ICP's translation terms are these
  /// normals; yaw aside, the horizontal is what a partial view of an upright object leaves open.
  double horizontal_constraint = 0.0;
  /// With RegistrationConfig::yaw_alternatives: other upright poses whose yaw differs from the
  /// best's by more than 20 deg, fitness at least alternative_min_fitness x the best's, best
  /// first (at most 5).
  std::vector<PoseAlternative> alternatives;
  int correspondences = 0;  // feature correspondences RANSAC started from
  double ms = 0.0;
};

/// A cloud prepared for registration: its FPFH descriptors (support feature_radius_voxels x
/// voxel_size_m), a k-d tree over them and one over its points. registerSurfaces on plain clouds
/// computes these for both on every call; prepared once, a segment's serve every candidate model
/// and a model's every later segment. Immutable; copies share the data. InputError as
/// registerSurfaces for an empty cloud, missing normals or a bad config (`name` names the cloud).
/// Thread safety: one thread at a time (PCL does not document its search structures as safe for
/// concurrent queries).
class SurfaceFeatures {
 public:
  SurfaceFeatures(const SurfaceCloud& cloud, const RegistrationConfig& config,
                  const std::string& name = "cloud");
  std::size_t size() const;
  /// Whether these were prepared with `config`'s descriptor support.
  bool preparedFor(const RegistrationConfig& config) const;

  struct Impl;  // PCL types (internal/surface_features_impl.h)
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

/// Registers `source` onto `target` (both with normals, in their own frames). Never throws for
/// unlucky data (converged = false with the reason); InputError for empty clouds, missing normals,
/// a bad config or a non-finite vertical translation.
/// `vertical_translation_m`: when known, T_target_source's z translation (metres). Two views of
/// one object standing on the floor in both frames differ by a yaw and a horizontal shift only;
/// without the floor a view whose faces are all vertical (a tall stack whose top the camera does
/// not see) fits itself slid up or down. RANSAC hypotheses take this z and ICP holds it.
RegistrationResult registerSurfaces(const SurfaceCloud& source, const SurfaceCloud& target,
                                    const RegistrationConfig& config,
                                    std::optional<double> vertical_translation_m = std::nullopt);
/// The same on prepared clouds; the result is identical. InputError also when either was prepared
/// with another descriptor support than `config`'s.
RegistrationResult registerSurfaces(const SurfaceFeatures& source, const SurfaceFeatures& target,
                                    const RegistrationConfig& config,
                                    std::optional<double> vertical_translation_m = std::nullopt);

}  // namespace strata::objects
