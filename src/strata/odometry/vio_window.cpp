#include "strata/odometry/internal/vio_window.h"

#include <ceres/ordered_groups.h>
#include <ceres/problem.h>

#include <Eigen/Dense>
#include <algorithm>
#include <set>

#include "strata/odometry/imu_factor.h"
#include "strata/odometry/reprojection_factor.h"

namespace strata::odometry::internal {

Eigen::Isometry3d Keyframe::T_W_B() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(pose[3], pose[0], pose[1], pose[2]).normalized().matrix();
  T.translation() = Eigen::Vector3d(pose + 4);
  return T;
}

void Keyframe::setPose(const Eigen::Matrix3d& R_W_B, const Eigen::Vector3d& p_W_B) {
  const Eigen::Quaterniond q(R_W_B);
  pose[0] = q.x();
  pose[1] = q.y();
  pose[2] = q.z();
  pose[3] = q.w();
  for (int k = 0; k < 3; ++k) pose[4 + k] = p_W_B[k];
}

ImuBias Keyframe::bias() const {
  ImuBias b;
  b.gyro_rad_s = Eigen::Vector3d(speed_bias + 3);
  b.accel_mps2 = Eigen::Vector3d(speed_bias + 6);
  return b;
}

Window::Window(const CameraRig& rig, double huber_whitened)
    : rig_(rig), loss_(std::make_unique<ceres::HuberLoss>(huber_whitened)) {}

void Window::clear() {
  keyframes.clear();
  landmarks.clear();
  prior.reset();
}

Eigen::Isometry3d Window::T_W_C(std::int64_t keyframe_id, bool right) const {
  return keyframe(keyframe_id).T_W_B() * (right ? rig_.T_B_Cr : rig_.T_B_Cl);
}

void Window::addObservations(std::int64_t id, const std::vector<FeatureObservation>& features) {
  for (const FeatureObservation& f : features) {
    const Eigen::Vector2d uv_left = rig_.left.toPixel(f.xy_left_norm);
    std::optional<Eigen::Vector2d> right;
    if (rig_.right && f.xy_right_norm) right = rig_.right->toPixel(*f.xy_right_norm);
    auto it = landmarks.find(f.track_id);
    if (it == landmarks.end()) {
      Landmark l;
      l.anchor_id = id;
      l.bearing = rig_.left.unproject(uv_left);
      it = landmarks.emplace(f.track_id, l).first;
    }
    it->second.observations.push_back({id, uv_left, right});
  }
}

void Window::triangulate(double min_depth_m, double max_depth_m) {
  for (auto& [track, l] : landmarks) {
    if (l.rho > 0.0) continue;
    // Midpoint method: minimise sum |(I - d d^T)(X - c)|^2 over the rays (c, d).
    std::vector<std::pair<Eigen::Isometry3d, Eigen::Vector3d>> rays;
    for (const Observation& o : l.observations) {
      rays.push_back({T_W_C(o.keyframe_id, false), rig_.left.unproject(o.uv_left)});
      if (o.uv_right)
        rays.push_back({T_W_C(o.keyframe_id, true), rig_.right->unproject(*o.uv_right)});
    }
    if (rays.size() < 2) continue;
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (const auto& [T, ray] : rays) {
      const Eigen::Vector3d d = (T.linear() * ray).normalized();
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
      A += P;
      b += P * T.translation();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A);
    // Two rays at angle a give eigenvalues ~(a^2 / 2, ..., 2): require a parallax of ~0.5 deg
    // (an 11 cm stereo baseline gives it out to 12 m), else the depth is mostly noise.
    if (eig.eigenvalues()(0) < 2e-5 * eig.eigenvalues()(2)) continue;
    const Eigen::Vector3d X = A.ldlt().solve(b);
    bool ok = true;
    for (const auto& [T, ray] : rays) {
      const double z = (T.inverse() * X).z();
      ok = ok && z > min_depth_m && z < max_depth_m;
    }
    const double z_anchor = (T_W_C(l.anchor_id, false).inverse() * X).z();
    if (ok) l.rho = 1.0 / z_anchor;
  }
}

std::vector<Factor> Window::buildFactors(const SolveSettings& s) const {
  std::vector<Factor> factors;
  auto* self = const_cast<Window*>(this);  // factors point at the blocks they will change
  if (!s.visual_only) {
    if (prior) {
      Factor f;
      f.cost = prior.get();
      f.blocks = prior->blockPointers();
      f.kind = FactorKind::kPrior;
      factors.push_back(std::move(f));
    }
    for (std::size_t k = 1; k < keyframes.size(); ++k) {
      Keyframe& a = self->keyframes[k - 1];
      Keyframe& b = self->keyframes[k];
      Factor f;
      f.owned.reset(ImuFactor::create(b.from_previous, s.gravity_W));
      f.cost = f.owned.get();
      f.blocks = {a.pose, a.speed_bias, b.pose, b.speed_bias};
      f.kind = FactorKind::kImu;
      f.keyframe_id = b.id;
      factors.push_back(std::move(f));
    }
  }
  const Eigen::Isometry3d T_Cr_Cl = rig_.T_B_Cr.inverse() * rig_.T_B_Cl;
  for (auto& entry : self->landmarks) {
    // NOTE: not a structured binding: clang 14 cannot capture one in the lambda below.
    const auto track = entry.first;
    Landmark& l = entry.second;
    if (!(l.rho > 0.0)) continue;
    const bool seen_elsewhere =
        std::any_of(l.observations.begin(), l.observations.end(),
                    [&](const Observation& o) { return o.keyframe_id != l.anchor_id; });
    if (!seen_elsewhere) continue;
    double* anchor_pose = self->keyframe(l.anchor_id).pose;
    auto add = [&](ceres::CostFunction* cost, std::vector<double*> blocks, std::int64_t id) {
      Factor f;
      f.owned.reset(cost);
      // A point behind the camera at the current estimate would fail the whole solve: skip it
      // this time (outlier removal drops it if it stays there).
      double r[2];
      if (!cost->Evaluate(blocks.data(), r, nullptr)) return;
      f.cost = cost;
      f.loss = loss_.get();
      f.blocks = std::move(blocks);
      f.kind = FactorKind::kReprojection;
      f.track_id = track;
      f.keyframe_id = id;
      f.sigma_px = s.pixel_sigma_px;
      factors.push_back(std::move(f));
    };
    for (const Observation& o : l.observations) {
      if (o.keyframe_id == l.anchor_id) {
        if (o.uv_right) {
          add(AnchorStereoFactor::create(l.bearing, T_Cr_Cl, *rig_.right, *o.uv_right,
                                         s.pixel_sigma_px),
              {&l.rho}, o.keyframe_id);
        }
        continue;
      }
      double* pose = self->keyframe(o.keyframe_id).pose;
      add(new ReprojectionCost(l.bearing, rig_.T_B_Cl, rig_.T_B_Cl, rig_.left, o.uv_left,
                               s.pixel_sigma_px),
          {anchor_pose, pose, &l.rho}, o.keyframe_id);
      if (o.uv_right) {
        add(new ReprojectionCost(l.bearing, rig_.T_B_Cl, rig_.T_B_Cr, *rig_.right, *o.uv_right,
                                 s.pixel_sigma_px),
            {anchor_pose, pose, &l.rho}, o.keyframe_id);
      }
    }
  }
  return factors;
}

ceres::Solver::Summary Window::solve(const std::vector<Factor>& factors, const SolveSettings& s) {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const Factor& f : factors) {
    problem.AddResidualBlock(const_cast<ceres::CostFunction*>(f.cost),
                             const_cast<ceres::LossFunction*>(f.loss), f.blocks);
  }
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (Keyframe& k : keyframes) {
    if (!problem.HasParameterBlock(k.pose)) problem.AddParameterBlock(k.pose, kPoseSize);
    problem.SetManifold(k.pose, &pose_manifold_);
    ordering->AddElementToGroup(k.pose, 1);
    if (problem.HasParameterBlock(k.speed_bias)) ordering->AddElementToGroup(k.speed_bias, 1);
  }
  for (auto& [track, l] : landmarks) {
    if (problem.HasParameterBlock(&l.rho)) ordering->AddElementToGroup(&l.rho, 0);
  }
  if (s.visual_only && !keyframes.empty())
    problem.SetParameterBlockConstant(keyframes.front().pose);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.linear_solver_ordering.reset(ordering);
  options.max_num_iterations = s.max_iterations;
  options.max_solver_time_in_seconds = s.max_solver_time_s;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary;
}

double Window::reprojectionErrorPx(const Factor& f) {
  double r[2];
  if (!f.cost->Evaluate(f.blocks.data(), r, nullptr)) return 1e9;
  return f.sigma_px * std::hypot(r[0], r[1]);
}

void Window::removeOutliers(const std::vector<Factor>& factors, double outlier_px) {
  std::set<std::pair<std::uint64_t, std::int64_t>> bad;
  for (const Factor& f : factors) {
    if (f.kind == FactorKind::kReprojection && reprojectionErrorPx(f) > outlier_px) {
      bad.insert({f.track_id, f.keyframe_id});
    }
  }
  for (auto it = landmarks.begin(); it != landmarks.end();) {
    Landmark& l = it->second;
    auto& obs = l.observations;
    obs.erase(std::remove_if(
                  obs.begin(), obs.end(),
                  [&](const Observation& o) {
                    return o.keyframe_id != l.anchor_id && bad.count({it->first, o.keyframe_id});
                  }),
              obs.end());
    // A bad anchor observation (or a point that went behind): start the track afresh.
    const bool bad_anchor = bad.count({it->first, l.anchor_id}) > 0;
    if (bad_anchor || (l.rho != 0.0 && !(l.rho > 0.0)) || obs.empty()) {
      it = landmarks.erase(it);
    } else {
      ++it;
    }
  }
}

void Window::marginaliseOldest(const std::vector<Factor>& factors) {
  Keyframe& oldest = keyframes.front();
  std::set<double*> drop = {oldest.pose, oldest.speed_bias};
  for (auto& [track, l] : landmarks) {
    if (l.anchor_id == oldest.id) drop.insert(&l.rho);
  }
  std::vector<LinearisedFactor> linearised;
  for (const Factor& f : factors) {
    const bool touches =
        std::any_of(f.blocks.begin(), f.blocks.end(), [&](double* b) { return drop.count(b) > 0; });
    if (touches || f.kind == FactorKind::kPrior) linearised.push_back({f.cost, f.loss, f.blocks});
  }
  std::map<double*, const ceres::Manifold*> manifolds;
  for (Keyframe& k : keyframes) manifolds[k.pose] = &pose_manifold_;
  std::unique_ptr<LinearPrior> next = marginalise(linearised, drop, manifolds);
  prior = std::move(next);
  // Landmarks anchored in the oldest keyframe live on, re-anchored in the next keyframe that saw
  // them, with their remaining observations (NOTE: those were also folded into the prior, so they
  // count twice: VINS-Mono's approximation, which keeps the window constrained by vision when
  // every track started in the same keyframe, as at standstill).
  for (auto it = landmarks.begin(); it != landmarks.end();) {
    Landmark& l = it->second;
    auto& obs = l.observations;
    obs.erase(std::remove_if(obs.begin(), obs.end(),
                             [&](const Observation& o) { return o.keyframe_id == oldest.id; }),
              obs.end());
    if (l.anchor_id == oldest.id && !obs.empty()) {
      const Eigen::Vector3d p_W = T_W_C(l.anchor_id, false) * (l.bearing / std::max(l.rho, 1e-9));
      l.anchor_id = obs.front().keyframe_id;
      l.bearing = rig_.left.unproject(obs.front().uv_left);
      const double z = (T_W_C(l.anchor_id, false).inverse() * p_W).z();
      l.rho = l.rho > 0.0 && z > 1e-3 ? 1.0 / z : 0.0;
    }
    it = obs.empty() ? landmarks.erase(it) : std::next(it);
  }
  keyframes.pop_front();
  if (!keyframes.empty()) keyframes.front().from_previous.reset();
}

}  // namespace strata::odometry::internal
