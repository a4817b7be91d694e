#include "strata/align/synthetic_sessions.h"

#include <cmath>
#include <random>
#include "strata/core/math_constants.h"

namespace strata::align {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

/// Camera looking along the circle's tangent (z forward, y down), with a little roll, pitch and
/// height change so the graph is not planar.
Isometry3d circlePose(const Vector3d& centre, double radius_m, double theta) {
  Eigen::Matrix3d camera_to_forward_x;  // columns: camera x, y, z in a frame looking along +x
  camera_to_forward_x << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Isometry3d T = Isometry3d::Identity();
  T.translation() = centre + Vector3d(radius_m * std::cos(theta), radius_m * std::sin(theta),
                                      1.0 + 0.2 * std::sin(3.0 * theta));
  T.linear() = (Eigen::AngleAxisd(theta + 0.5 * kPi, Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.05 * std::sin(2.0 * theta), Vector3d::UnitX()) *
                Eigen::AngleAxisd(0.04 * std::cos(5.0 * theta), Vector3d::UnitY()))
                   .toRotationMatrix() *
               camera_to_forward_x;
  return T;
}

/// Exp of a (translation, rotation vector) perturbation, decoupled as in the graph's residual.
Isometry3d perturbation(std::mt19937_64& rng, double sigma_m, double sigma_rad) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Vector3d t(sigma_m * n(rng), sigma_m * n(rng), sigma_m * n(rng));
  const Vector3d r(sigma_rad * n(rng), sigma_rad * n(rng), sigma_rad * n(rng));
  Isometry3d E = Isometry3d::Identity();
  E.translation() = t;
  if (r.norm() > 0.0) E.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  return E;
}

store::Matrix6d information(double sigma_m, double sigma_rad) {
  store::Matrix6d info = store::Matrix6d::Zero();
  info.diagonal() << Vector3d::Constant(1.0 / (sigma_m * sigma_m)),
      Vector3d::Constant(1.0 / (sigma_rad * sigma_rad));
  return info;
}

double angleBetween(const Isometry3d& x, const Isometry3d& y) {
  return Eigen::AngleAxisd(x.linear().transpose() * y.linear()).angle();
}

std::vector<Isometry3d> truePath(const SyntheticGraphConfig& c, int session) {
  const double ring = 2.0 * kPi * session / c.sessions;
  const Vector3d centre(c.centre_offset_m * std::cos(ring), c.centre_offset_m * std::sin(ring), 0);
  const double start = 0.37 * ring;  // sessions start at different places on the circle
  std::vector<Isometry3d> path;
  for (int k = 0; k < c.keyframes_per_session; ++k) {
    const double theta = start + 2.0 * kPi * c.laps * k / (c.keyframes_per_session - 1);
    path.push_back(circlePose(centre, c.radius_m, theta));
  }
  return path;
}

/// A session frame as odometry makes one: origin near the first camera, random yaw (gravity
/// fixes roll and pitch).
Isometry3d randomSessionFrame(const Isometry3d& T_W_C0, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> yaw(-kPi, kPi), offset(-0.5, 0.5);
  Isometry3d T = Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw(rng), Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = T_W_C0.translation() + Vector3d(offset(rng), offset(rng), offset(rng));
  return T;
}

std::vector<Isometry3d> driftedOdometry(const std::vector<Isometry3d>& truth,
                                        const Isometry3d& T_W_S, const SyntheticGraphConfig& c,
                                        std::mt19937_64& rng) {
  std::vector<Isometry3d> T_W_odometry{truth.front()};
  for (std::size_t k = 1; k < truth.size(); ++k) {
    T_W_odometry.push_back(T_W_odometry.back() * truth[k - 1].inverse() * truth[k] *
                           perturbation(rng, c.odometry_sigma_m, c.odometry_sigma_rad));
  }
  std::vector<Isometry3d> T_S_C;
  for (const Isometry3d& T_W_C : T_W_odometry) T_S_C.push_back(T_W_S.inverse() * T_W_C);
  return T_S_C;
}

void addLoop(SyntheticGraph& g, const SyntheticGraphConfig& c, std::size_t sa, std::size_t ka,
             std::size_t sb, std::size_t kb, std::mt19937_64& rng) {
  GraphLoop loop;
  loop.session_a = sa, loop.keyframe_a = ka, loop.session_b = sb, loop.keyframe_b = kb;
  loop.T_a_b = g.T_W_C_true[sa][ka].inverse() * g.T_W_C_true[sb][kb] *
               perturbation(rng, c.loop_sigma_m, c.loop_sigma_rad);
  loop.information = c.information_inflation > 0.0
                         ? information(c.information_inflation * c.loop_sigma_m,
                                       c.information_inflation * c.loop_sigma_rad)
                         : store::Matrix6d(store::Matrix6d::Identity() * 1e4);
  g.loops.push_back(loop);
}

/// Nearest keyframe of session sb to keyframe (sa, ka) that faces alike, at least `min_gap`
/// keyframes away when sa == sb; -1 when none is within loop_distance_m.
int nearestPartner(const SyntheticGraph& g, const SyntheticGraphConfig& c, std::size_t sa,
                   std::size_t ka, std::size_t sb) {
  int best = -1;
  double best_distance = c.loop_distance_m;
  const Isometry3d& pose_a = g.T_W_C_true[sa][ka];
  for (std::size_t kb = 0; kb < g.T_W_C_true[sb].size(); ++kb) {
    if (sa == sb && (kb < ka + static_cast<std::size_t>(c.intra_session_min_gap))) continue;
    const Isometry3d& pose_b = g.T_W_C_true[sb][kb];
    const double distance = (pose_a.translation() - pose_b.translation()).norm();
    if (distance < best_distance && angleBetween(pose_a, pose_b) < 0.5) {
      best = static_cast<int>(kb);
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace

SyntheticGraph makeSyntheticGraph(const SyntheticGraphConfig& c) {
  std::mt19937_64 rng(c.seed);
  SyntheticGraph g;
  for (int s = 0; s < c.sessions; ++s) {
    g.T_W_C_true.push_back(truePath(c, s));
    g.T_W_S_true.push_back(s == 0 ? Isometry3d::Identity()
                                  : randomSessionFrame(g.T_W_C_true.back().front(), rng));
    GraphSession session{driftedOdometry(g.T_W_C_true.back(), g.T_W_S_true.back(), c, rng), {}};
    if (c.information_inflation > 0.0) {
      session.odometry_information.assign(
          session.T_S_C.size() - 1, information(c.information_inflation * c.odometry_sigma_m,
                                                c.information_inflation * c.odometry_sigma_rad));
    }
    g.sessions.push_back(std::move(session));
  }
  for (std::size_t sa = 0; sa < g.sessions.size(); ++sa) {
    for (std::size_t sb = sa; sb < g.sessions.size(); ++sb) {
      for (std::size_t ka = 0; ka < g.T_W_C_true[sa].size(); ka += c.loop_every) {
        const int kb = nearestPartner(g, c, sa, ka, sb);
        if (kb >= 0) addLoop(g, c, sa, ka, sb, static_cast<std::size_t>(kb), rng);
      }
    }
  }
  return g;
}

void addRandomFalseLoops(SyntheticGraph& g, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> session(0, g.sessions.size() - 1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int added = 0; added < count;) {
    const std::size_t sa = session(rng), sb = session(rng);
    const std::size_t ka =
        std::uniform_int_distribution<std::size_t>(0, g.sessions[sa].T_S_C.size() - 1)(rng);
    const std::size_t kb =
        std::uniform_int_distribution<std::size_t>(0, g.sessions[sb].T_S_C.size() - 1)(rng);
    const Isometry3d T_true = g.T_W_C_true[sa][ka].inverse() * g.T_W_C_true[sb][kb];
    if (T_true.translation().norm() < 2.0) continue;
    GraphLoop loop;
    loop.session_a = sa, loop.keyframe_a = ka, loop.session_b = sb, loop.keyframe_b = kb;
    const Vector3d axis = Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
    loop.T_a_b = Eigen::Translation3d(Vector3d(unit(rng), unit(rng), unit(rng)) / std::sqrt(3.0)) *
                 Eigen::AngleAxisd(0.5 * unit(rng), axis);
    loop.information = g.loops.empty() ? store::Matrix6d::Identity() * 1e4 : g.loops[0].information;
    g.loops.push_back(loop);
    ++added;
  }
}

void addAgreeingFalseLoops(SyntheticGraph& g, std::size_t session, int count,
                           const Isometry3d& T_wrong, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Isometry3d T_W_S_wrong = g.T_W_S_true[session] * T_wrong;
  const std::vector<Isometry3d>& T_S_C = g.sessions[session].T_S_C;
  for (int added = 0; added < count; ++added) {
    std::size_t other = std::uniform_int_distribution<std::size_t>(0, g.sessions.size() - 2)(rng);
    if (other >= session) ++other;
    const std::size_t ka =
        std::uniform_int_distribution<std::size_t>(0, g.sessions[other].T_S_C.size() - 1)(rng);
    const std::size_t kb = std::uniform_int_distribution<std::size_t>(0, T_S_C.size() - 1)(rng);
    GraphLoop loop;
    loop.session_a = other, loop.keyframe_a = ka, loop.session_b = session, loop.keyframe_b = kb;
    loop.T_a_b = g.T_W_C_true[other][ka].inverse() * T_W_S_wrong * T_S_C[kb];
    loop.information = g.loops.empty() ? store::Matrix6d::Identity() * 1e4 : g.loops[0].information;
    g.loops.push_back(loop);
  }
}

std::vector<std::vector<Isometry3d>> odometryInTrueFrame(const SyntheticGraph& g) {
  std::vector<std::vector<Isometry3d>> T_W_C(g.sessions.size());
  for (std::size_t s = 0; s < g.sessions.size(); ++s) {
    for (const Isometry3d& T_S_C : g.sessions[s].T_S_C) {
      T_W_C[s].push_back(g.T_W_S_true[s] * T_S_C);
    }
  }
  return T_W_C;
}

double translationRmse(const std::vector<std::vector<Isometry3d>>& T_W_C, const SyntheticGraph& g) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t s = 0; s < T_W_C.size(); ++s) {
    for (std::size_t k = 0; k < T_W_C[s].size(); ++k) {
      sum += (T_W_C[s][k].translation() - g.T_W_C_true[s][k].translation()).squaredNorm();
      ++count;
    }
  }
  return count == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(count));
}

}  // namespace strata::align
