// Registration of two surface clouds: FPFH correspondences (feature_neighbours per source point)
// -> RANSAC over them (yaw + translation from 2 pairs, or upright 6-DoF hypotheses) -> the best
// hypotheses scored on the whole clouds -> point-to-plane ICP (6 DoF; a tilted result refused).
//
// NOTE: the RANSAC loop is ours rather than pcl::SampleConsensusPrerejective because (1) it
// searches 4 DoF (objects stand on the floor: 2-point samples, far fewer draws than 3-point 6-DoF
// samples nearly all of which tilt), which Prerejective cannot be told; (2) it draws from its own
// std::mt19937 seeded with config.seed, where Prerejective calls the process-wide rand() (shared
// state between threads); (3) it keeps several distinct hypotheses, so a symmetric part that wins
// the correspondence vote does not hide the right pose from the whole-cloud check.
#include "strata/core/clock.h"
#include "strata/objects/object_registration.h"

#include <pcl/common/transforms.h>
#include <pcl/exceptions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/correspondence_estimation.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include "strata/core/error.h"
#include "strata/core/math_constants.h"
#include "strata/objects/internal/registration_ransac.h"
#include "strata/objects/internal/surface_features_impl.h"

namespace strata::objects {

namespace {

/// Hypotheses with the most correspondence inliers scored on the whole clouds, and of those the
/// best few refined by ICP: enough for a symmetric object's two or four equivalent poses.
constexpr std::size_t kHypothesesScored = 8;
constexpr std::size_t kHypothesesRefined = 3;

std::string degrees(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f deg", value);
  return text;
}

/// Each source point with a finite descriptor paired with the target points of the `neighbours`
/// nearest ones.
std::vector<Correspondence> matchFeatures(const SurfaceFeatures::Impl& source,
                                          const SurfaceFeatures::Impl& target, int neighbours) {
  std::vector<Correspondence> out;
  if (target.finite_fpfh->empty()) return out;
  std::vector<int> nearest(static_cast<std::size_t>(neighbours));
  std::vector<float> distance(static_cast<std::size_t>(neighbours));
  for (std::size_t k = 0; k < source.finite_fpfh->size(); ++k) {
    const int found = target.descriptor_tree.nearestKSearch((*source.finite_fpfh)[k], neighbours,
                                                            nearest, distance);
    for (int j = 0; j < found; ++j) {
      out.push_back(
          {source.finite_index[k],
           target.finite_index[static_cast<std::size_t>(nearest[static_cast<std::size_t>(j)])]});
    }
  }
  return out;
}

/// Share of source points with a target point within `inlier_m` after `T`, and their RMS distance.
struct Fit {
  double fitness = 0.0;
  double rmse_m = 0.0;
  double horizontal_constraint = 0.0;  // RegistrationResult's, over the inliers
};

/// The smaller eigenvalue of the mean of n_xy n_xy^T (2x2, symmetric) over the normals summed
/// into (xx, xy, yy) from `count` normals: how strongly point-to-plane terms hold the weakest
/// horizontal direction.
double weakestHorizontal(double xx, double xy, double yy, std::size_t count) {
  if (count == 0) return 0.0;
  const double n = static_cast<double>(count);
  const double mean = 0.5 * (xx + yy) / n;
  const double half_gap = std::hypot(0.5 * (xx - yy), xy) / n;
  return std::max(0.0, mean - half_gap);
}

Fit scoreFit(const Cloud& source, const pcl::search::KdTree<pcl::PointNormal>& target_tree,
             const Eigen::Matrix4f& T, float inlier_m) {
  std::vector<int> nearest(1);
  std::vector<float> squared(1);
  std::size_t inliers = 0;
  double sum_squared = 0.0;
  double xx = 0.0, xy = 0.0, yy = 0.0;  // target normals' horizontal parts at the inliers
  const Cloud& target = *target_tree.getInputCloud();
  pcl::PointNormal moved;
  for (const pcl::PointNormal& p : source) {
    moved.getVector4fMap() = T * p.getVector4fMap();
    if (target_tree.nearestKSearch(moved, 1, nearest, squared) == 1 &&
        squared[0] <= inlier_m * inlier_m) {
      ++inliers;
      sum_squared += squared[0];
      const pcl::PointNormal& q = target[static_cast<std::size_t>(nearest[0])];
      xx += double(q.normal_x) * q.normal_x;
      xy += double(q.normal_x) * q.normal_y;
      yy += double(q.normal_y) * q.normal_y;
    }
  }
  Fit fit;
  if (inliers > 0) {
    fit.fitness = static_cast<double>(inliers) / static_cast<double>(source.size());
    fit.rmse_m = std::sqrt(sum_squared / static_cast<double>(inliers));
    fit.horizontal_constraint = weakestHorizontal(xx, xy, yy, inliers);
  }
  return fit;
}

/// Drops pairs whose normals differ by more than 60 deg: near thin parts (a board, a chair leg)
/// the nearest point is often on the far side, and those pairs pull the fit off by millimetres.
void keepCompatibleNormals(const Cloud& moved, const Cloud& target, pcl::Correspondences& pairs) {
  constexpr float kMinCosine = 0.5f;
  pcl::Correspondences kept;
  kept.reserve(pairs.size());
  for (const pcl::Correspondence& c : pairs) {
    const float cosine = moved[static_cast<std::size_t>(c.index_query)].getNormalVector3fMap().dot(
        target[static_cast<std::size_t>(c.index_match)].getNormalVector3fMap());
    if (cosine >= kMinCosine) kept.push_back(c);
  }
  pairs.swap(kept);
}

/// One Gauss-Newton step of point-to-plane ICP (Low 2004, the small-angle linearisation), with
/// point-to-point rows of weight kPointWeight: partial views often see a direction constrained by
/// no plane at all (two views that share only the top and one side of a box), where the
/// point-to-plane normal matrix is singular (PCL's TransformationEstimationPointToPlaneLLS then
/// inverts it into NaN). The nearest points hold such a direction without biasing the others.
Eigen::Matrix4f pointToPlaneStep(const Cloud& moved, const Cloud& target,
                                 const pcl::Correspondences& pairs, bool fixed_z) {
  constexpr double kPointWeight = 0.1;
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
  auto addRow = [&](const Eigen::Matrix<double, 6, 1>& J, double residual, double weight) {
    H.noalias() += weight * J * J.transpose();
    g.noalias() += weight * J * residual;
  };
  for (const pcl::Correspondence& c : pairs) {
    const Eigen::Vector3d s =
        moved[static_cast<std::size_t>(c.index_query)].getVector3fMap().cast<double>();
    const pcl::PointNormal& t = target[static_cast<std::size_t>(c.index_match)];
    const Eigen::Vector3d d = t.getVector3fMap().cast<double>() - s;
    const Eigen::Vector3d n = t.getNormalVector3fMap().cast<double>();
    Eigen::Matrix<double, 6, 1> J;
    J << s.cross(n), n;  // d(n . (R s + t)) / d(omega, t) at identity
    addRow(J, n.dot(d), 1.0);
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
      J << s.cross(e), e;
      addRow(J, d[axis], kPointWeight);
    }
  }
  if (fixed_z) {  // the step leaves the vertical translation where it is
    H.row(5).setZero();
    H.col(5).setZero();
    H(5, 5) = 1.0;
    g(5) = 0.0;
  }
  const Eigen::Matrix<double, 6, 1> x = H.ldlt().solve(g);
  Eigen::Matrix4d step = Eigen::Matrix4d::Identity();
  const double angle = x.head<3>().norm();
  if (angle > 0.0) {
    step.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, x.head<3>() / angle).toRotationMatrix();
  }
  step.topRightCorner<3, 1>() = x.tail<3>();
  return step.cast<float>();
}

/// Point-to-plane ICP: PCL's correspondence search (kd-tree), pairs within `max_distance_m` with
/// compatible normals, Gauss-Newton steps as above until they fall below 10 um and 10 urad. With
/// `fixed_z_m` the translation's z is held there.
Eigen::Matrix4f iterateIcp(
    pcl::registration::CorrespondenceEstimation<pcl::PointNormal, pcl::PointNormal, float>& search,
    const Cloud::Ptr& source, const Cloud::Ptr& target, const Eigen::Matrix4f& guess,
    double max_distance_m, int iterations, std::optional<float> fixed_z_m) {
  Eigen::Matrix4f T = guess;
  Cloud::Ptr moved(new Cloud);
  pcl::Correspondences pairs;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    pcl::transformPointCloudWithNormals(*source, *moved, T);
    search.setInputSource(moved);
    search.determineCorrespondences(pairs, max_distance_m);
    keepCompatibleNormals(*moved, *target, pairs);
    if (pairs.size() < 6) break;  // the 6 DoF are not determined
    const Eigen::Matrix4f step = pointToPlaneStep(*moved, *target, pairs, fixed_z_m.has_value());
    if (!step.allFinite()) break;
    T = step * T;
    if (fixed_z_m) T(2, 3) = *fixed_z_m;  // a small tilt of the step moves it a little
    const float turned =
        std::acos(std::clamp((step.topLeftCorner<3, 3>().trace() - 1.0f) / 2.0f, -1.0f, 1.0f));
    if (step.topRightCorner<3, 1>().norm() < 1e-5f && turned < 1e-5f) break;
  }
  return T;
}

/// Coarse then fine ICP from a RANSAC hypothesis. NOTE: the coarse stage (wide correspondence
/// distance) matters on partial views: there the fine stage alone leaves the directions few
/// planes constrain where the hypothesis put them (1-2 cm off on chairs seen from 90 deg apart,
/// within 6 mm with the coarse stage).
Eigen::Matrix4f refineIcp(const Cloud::Ptr& source, const SurfaceFeatures::Impl& target_features,
                          const Eigen::Matrix4f& guess, const RegistrationConfig& config,
                          std::optional<float> fixed_z_m) {
  const Cloud::Ptr& target = target_features.cloud;
  pcl::registration::CorrespondenceEstimation<pcl::PointNormal, pcl::PointNormal, float> search;
  search.setInputTarget(target);
  search.setSearchMethodTarget(target_features.point_tree, true);  // built once, with the target
  const Eigen::Matrix4f coarse = iterateIcp(search, source, target, guess,
                                            config.icp_coarse_distance_voxels * config.voxel_size_m,
                                            config.icp_iterations, fixed_z_m);
  return iterateIcp(search, source, target, coarse,
                    config.icp_max_distance_voxels * config.voxel_size_m, config.icp_iterations,
                    fixed_z_m);
}

/// The hypotheses scored on the whole clouds; the best few refined by ICP; of those, the best
/// fit that stays upright. nullopt when ICP tilted all of them.
struct Refined {
  Eigen::Matrix4f T;
  Fit fit;
};
double targetCoverage(const Cloud& source, const Cloud& target, const Eigen::Matrix4f& T,
                      const RegistrationConfig& config);

/// Yaw (radians, about +z) of T's rotation.
float yawOf(const Eigen::Matrix4f& T) { return std::atan2(T(1, 0), T(0, 0)); }

/// |a - b| wrapped into [0, pi].
float yawDifference(float a, float b) {
  const float d = std::fmod(std::abs(a - b), 2.0f * static_cast<float>(kPi));
  return std::min(d, 2.0f * static_cast<float>(kPi) - d);
}

std::vector<Refined> refineAll(const Cloud::Ptr& source, const SurfaceFeatures::Impl& target,
                               const std::vector<Hypothesis>& hypotheses,
                               const RegistrationConfig& config, std::optional<float> fixed_z_m);

/// The best pose turned by a quarter, a half and three quarters about the source's centre (in the
/// target frame), refined like the hypotheses: the poses a near-square or symmetric footprint
/// confuses, offered to the caller's own check when RANSAC's vote missed them.
std::vector<Refined> turnedAlternatives(const Cloud::Ptr& source,
                                        const SurfaceFeatures::Impl& target,
                                        const Eigen::Matrix4f& best,
                                        const RegistrationConfig& config,
                                        std::optional<float> fixed_z_m) {
  Eigen::Vector4f centre = Eigen::Vector4f::Zero();
  for (const pcl::PointNormal& p : *source) centre += p.getVector4fMap();
  centre /= static_cast<float>(std::max<std::size_t>(1, source->size()));
  centre.w() = 1.0f;
  const Eigen::Vector3f c = (best * centre).head<3>();
  std::vector<Hypothesis> turned;
  for (const int quarter : {1, 2, 3}) {
    Eigen::Matrix4f turn = Eigen::Matrix4f::Identity();
    turn.topLeftCorner<3, 3>() =
        Eigen::AngleAxisf(quarter * 0.5f * static_cast<float>(kPi), Eigen::Vector3f::UnitZ())
            .toRotationMatrix();
    turn.topRightCorner<3, 1>() = c - turn.topLeftCorner<3, 3>() * c;
    Hypothesis h;
    h.T = turn * best;
    turned.push_back(h);
  }
  return refineAll(source, target, turned, config, fixed_z_m);
}

std::vector<Refined> refineAll(const Cloud::Ptr& source, const SurfaceFeatures::Impl& target,
                               const std::vector<Hypothesis>& hypotheses,
                               const RegistrationConfig& config, std::optional<float> fixed_z_m) {
  const pcl::search::KdTree<pcl::PointNormal>& target_tree = *target.point_tree;
  const float inlier_m = config.inlier_distance_voxels * config.voxel_size_m;
  std::vector<Refined> out;
  for (const Hypothesis& h : hypotheses) {
    Eigen::Matrix4f guess = h.T;
    if (fixed_z_m) guess(2, 3) = *fixed_z_m;
    const Eigen::Matrix4f T = refineIcp(source, target, guess, config, fixed_z_m);
    if (tiltDeg(T) > config.max_tilt_deg) continue;
    out.push_back({T, scoreFit(*source, target_tree, T, inlier_m)});
  }
  return out;
}

std::optional<Refined> refineBest(const Cloud::Ptr& source, const SurfaceFeatures::Impl& target,
                                  const std::vector<Hypothesis>& hypotheses,
                                  const RegistrationConfig& config,
                                  std::optional<float> fixed_z_m,
                                  std::vector<Refined>* others = nullptr) {
  const pcl::search::KdTree<pcl::PointNormal>& target_tree = *target.point_tree;
  const float inlier_m = config.inlier_distance_voxels * config.voxel_size_m;
  std::vector<std::pair<double, Eigen::Matrix4f>> scored;
  for (const Hypothesis& h : hypotheses) {
    Eigen::Matrix4f T = h.T;
    if (fixed_z_m) T(2, 3) = *fixed_z_m;
    scored.emplace_back(scoreFit(*source, target_tree, T, inlier_m).fitness, T);
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::optional<Refined> best;
  for (std::size_t i = 0; i < std::min(kHypothesesRefined, scored.size()); ++i) {
    const Eigen::Matrix4f T = refineIcp(source, target, scored[i].second, config, fixed_z_m);
    if (tiltDeg(T) > config.max_tilt_deg) continue;
    const Fit fit = scoreFit(*source, target_tree, T, inlier_m);
    if (others != nullptr) others->push_back({T, fit});
    if (!best || fit.fitness > best->fit.fitness) best = Refined{T, fit};
  }
  return best;
}

/// The refined poses other than the best that differ from it in yaw by more than 20 deg (and
/// from each other), fitness at least alternative_min_fitness x the best's, best first, at most 5.
std::vector<PoseAlternative> distinctAlternatives(std::vector<Refined> refined,
                                                  const Refined& best, const Cloud& source,
                                                  const Cloud& target,
                                                  const RegistrationConfig& config) {
  constexpr float kDistinctYaw = 20.0f * static_cast<float>(kPi) / 180.0f;
  constexpr std::size_t kMaxAlternatives = 5;
  std::stable_sort(refined.begin(), refined.end(),
                   [](const Refined& a, const Refined& b) { return a.fit.fitness > b.fit.fitness; });
  std::vector<float> taken = {yawOf(best.T)};
  std::vector<PoseAlternative> out;
  for (const Refined& r : refined) {
    if (out.size() >= kMaxAlternatives) break;
    if (r.fit.fitness < config.alternative_min_fitness * best.fit.fitness) break;
    const float yaw = yawOf(r.T);
    if (std::any_of(taken.begin(), taken.end(),
                    [&](float t) { return yawDifference(t, yaw) < kDistinctYaw; })) {
      continue;
    }
    taken.push_back(yaw);
    PoseAlternative alternative;
    alternative.T_target_source.matrix() = r.T.cast<double>();
    alternative.fitness = r.fit.fitness;
    alternative.horizontal_constraint = r.fit.horizontal_constraint;
    alternative.target_coverage = targetCoverage(source, target, r.T, config);
    out.push_back(alternative);
  }
  return out;
}

/// scoreFit the other way round: the target's points against the source moved by `T`.
double targetCoverage(const Cloud& source, const Cloud& target, const Eigen::Matrix4f& T,
                      const RegistrationConfig& config) {
  Cloud::Ptr moved(new Cloud);
  pcl::transformPointCloudWithNormals(source, *moved, T);
  pcl::search::KdTree<pcl::PointNormal> moved_tree;
  moved_tree.setInputCloud(moved);
  return scoreFit(target, moved_tree, Eigen::Matrix4f::Identity(),
                  config.inlier_distance_voxels * config.voxel_size_m)
      .fitness;
}

}  // namespace

void RegistrationConfig::validate() const {
  auto require = [](bool ok, const char* field, const std::string& why) {
    if (!ok) throw InputError(std::string("RegistrationConfig.") + field + " " + why);
  };
  require(std::isfinite(voxel_size_m) && voxel_size_m > 0.0f, "voxel_size_m", "must be > 0");
  require(feature_radius_voxels > 1.0f, "feature_radius_voxels", "must be > 1");
  require(inlier_distance_voxels > 0.0f, "inlier_distance_voxels", "must be > 0");
  require(ransac_iterations > 0, "ransac_iterations", "must be > 0");
  require(ransac_samples >= 3 && ransac_samples <= 8, "ransac_samples", "must be in 3..8");
  require(edge_similarity >= 0.0f && edge_similarity < 1.0f, "edge_similarity",
          "must be in [0, 1)");
  require(icp_iterations >= 0, "icp_iterations", "must be >= 0");
  require(icp_max_distance_voxels > 0.0f, "icp_max_distance_voxels", "must be > 0");
  require(icp_coarse_distance_voxels >= icp_max_distance_voxels, "icp_coarse_distance_voxels",
          "must be >= icp_max_distance_voxels");
  require(max_tilt_deg > 0.0f && max_tilt_deg <= 180.0f, "max_tilt_deg", "must be in (0, 180]");
  require(feature_neighbours >= 1 && feature_neighbours <= 8, "feature_neighbours",
          "must be in 1..8");
  require(alternative_min_fitness > 0.0f && alternative_min_fitness <= 1.0f,
          "alternative_min_fitness", "must be in (0, 1]");
}

RegistrationResult registerSurfaces(const SurfaceCloud& source, const SurfaceCloud& target,
                                    const RegistrationConfig& config,
                                    std::optional<double> vertical_translation_m) {
  const auto start = std::chrono::steady_clock::now();
  const SurfaceFeatures source_features(source, config, "source cloud");
  const SurfaceFeatures target_features(target, config, "target cloud");
  RegistrationResult result =
      registerSurfaces(source_features, target_features, config, vertical_translation_m);
  result.ms =
      msSince(start);
  return result;
}

RegistrationResult registerSurfaces(const SurfaceFeatures& source_features,
                                    const SurfaceFeatures& target_features,
                                    const RegistrationConfig& config,
                                    std::optional<double> vertical_translation_m) {
  const auto start = std::chrono::steady_clock::now();
  config.validate();
  if (!source_features.preparedFor(config) || !target_features.preparedFor(config)) {
    throw InputError("registerSurfaces: features prepared with another descriptor support than " +
                     std::to_string(config.feature_radius_voxels * config.voxel_size_m) + " m");
  }
  if (vertical_translation_m && !std::isfinite(*vertical_translation_m)) {
    throw InputError("registerSurfaces: the vertical translation is not finite");
  }
  const std::optional<float> fixed_z_m =
      vertical_translation_m ? std::optional<float>(static_cast<float>(*vertical_translation_m))
                             : std::nullopt;
  const SurfaceFeatures::Impl& source = source_features.impl();
  const SurfaceFeatures::Impl& target = target_features.impl();
  RegistrationResult result;
  auto finish = [&](const std::string& reason) {
    result.reason = reason;
    result.converged = reason.empty();
    result.ms =
        msSince(start);
    return result;
  };
  if (!source.failure.empty() || !target.failure.empty()) {
    return finish("PCL failed: " + (source.failure.empty() ? target.failure : source.failure));
  }
  try {
    const std::vector<Correspondence> matches =
        matchFeatures(source, target, config.feature_neighbours);
    result.correspondences = static_cast<int>(matches.size());
    const std::vector<Hypothesis> hypotheses =
        config.four_dof
            ? ransacYaw(source.points, target.points, matches, config, kHypothesesScored)
            : ransacUpright(source.points, target.points, matches, config, kHypothesesScored);
    if (hypotheses.empty()) {
      const std::string kind = config.four_dof
                                   ? "upright (yaw + translation)"
                                   : "within " + degrees(config.max_tilt_deg) + " of upright";
      return finish("no RANSAC hypothesis " + kind + " from " + std::to_string(matches.size()) +
                    " feature correspondences");
    }
    std::vector<Refined> others;
    const std::optional<Refined> best = refineBest(source.cloud, target, hypotheses, config,
                                                   fixed_z_m, config.yaw_alternatives ? &others : nullptr);
    if (!best) {
      return finish("ICP tilted every hypothesis by more than " + degrees(config.max_tilt_deg));
    }
    const Eigen::Matrix4f& best_T = best->T;
    const Fit& best_fit = best->fit;
    result.T_target_source.matrix() = best_T.cast<double>();
    result.fitness = best_fit.fitness;
    result.rmse_m = best_fit.rmse_m;
    result.horizontal_constraint = best_fit.horizontal_constraint;
    result.target_coverage = targetCoverage(*source.cloud, *target.cloud, best_T, config);
    if (best_fit.fitness <= 0.0) return finish("no source point near the target after ICP");
    if (config.yaw_alternatives) {
      for (Refined& r : turnedAlternatives(source.cloud, target, best_T, config, fixed_z_m)) {
        others.push_back(r);
      }
      result.alternatives =
          distinctAlternatives(std::move(others), *best, *source.cloud, *target.cloud, config);
    }
    return finish("");
  } catch (const pcl::PCLException& e) {
    return finish(std::string("PCL failed: ") + e.what());
  }
}

}  // namespace strata::objects
