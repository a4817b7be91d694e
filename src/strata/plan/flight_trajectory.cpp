// Corner rounding, time parameterisation and the collision check of trajectories (contract in
// trajectory.h).
#include "strata/plan/flight_trajectory.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "strata/core/error.h"

namespace strata::plan {
namespace {

// Turns below this (radians) are straight: no curve, no stop.
constexpr float kStraightTurnRad = 1e-4f;

/// One point of the sampled geometry. `blame_a`, `blame_b`: the vertices whose rounding shaped
/// it (a curve: its vertex twice; a straight piece: the vertices at its ends).
struct GeoPoint {
  Eigen::Vector3f p_W;
  Eigen::Vector3f tangent = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  float curvature = 0.0f;  // 1/m
  bool stop = false;       // a sharp corner: speed 0
  int blame_a = 0, blame_b = 0;
};

std::vector<Eigen::Vector3f> dropRepeats(const std::vector<Eigen::Vector3f>& path_W) {
  std::vector<Eigen::Vector3f> out;
  for (const Eigen::Vector3f& p : path_W) {
    if (!p.allFinite()) throw InputError("makeTrajectory: the path has a non-finite point");
    if (out.empty() || (p - out.back()).norm() > 1e-6f) out.push_back(p);
  }
  return out;
}

float turnAngle(const Eigen::Vector3f& u_in, const Eigen::Vector3f& u_out) {
  return std::acos(std::clamp(u_in.dot(u_out), -1.0f, 1.0f));
}

void appendLine(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float step_m, int blame_a,
                int blame_b, std::vector<GeoPoint>& out) {
  const float length_m = (b - a).norm();
  if (length_m < 1e-6f) return;
  const Eigen::Vector3f u = (b - a) / length_m;
  out.back().tangent = u;
  const int n = std::max(1, static_cast<int>(std::ceil(length_m / step_m)));
  for (int k = 1; k <= n; ++k) {
    GeoPoint g{a + (b - a) * (static_cast<float>(k) / n)};
    g.tangent = u;
    g.blame_a = blame_a;
    g.blame_b = blame_b;
    out.push_back(g);
  }
}

/// The quadratic Bezier q0 -> q2 with control point p, without q0 (already in `out`). Chords are
/// at most step_m: |B'| <= 2d and the curve has n >= 2d / step pieces.
void appendCorner(const Eigen::Vector3f& q0, const Eigen::Vector3f& p, const Eigen::Vector3f& q2,
                  float step_m, int vertex, std::vector<GeoPoint>& out) {
  const float d = (p - q0).norm();
  const int n = std::max(2, static_cast<int>(std::ceil(2.0f * d / step_m)));
  const Eigen::Vector3f second = 2.0f * (q0 - 2.0f * p + q2);
  for (int k = 1; k <= n; ++k) {
    const float t = static_cast<float>(k) / n;
    GeoPoint g{(1 - t) * (1 - t) * q0 + 2 * t * (1 - t) * p + t * t * q2};
    const Eigen::Vector3f first = 2.0f * (1 - t) * (p - q0) + 2.0f * t * (q2 - p);
    const float speed = first.norm();
    g.tangent = first / speed;
    g.curvature = first.cross(second).norm() / (speed * speed * speed);
    const Eigen::Vector3f across = second - g.tangent * g.tangent.dot(second);
    if (across.norm() > 0.0f) g.normal = across.normalized();
    g.blame_a = g.blame_b = vertex;
    out.push_back(g);
  }
}

/// The rounded polyline, sampled: vertices v, corner cut d per vertex (0 at the ends).
std::vector<GeoPoint> buildGeometry(const std::vector<Eigen::Vector3f>& v,
                                    const std::vector<float>& d, float step_m) {
  const int n = static_cast<int>(v.size());
  std::vector<GeoPoint> out{GeoPoint{v[0]}};
  for (int i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3f u = (v[i + 1] - v[i]).normalized();
    const Eigen::Vector3f a = v[i] + d[i] * u;
    const Eigen::Vector3f b = v[i + 1] - d[i + 1] * u;
    appendLine(a, b, step_m, i, i + 1, out);
    if (i + 2 >= n) break;
    const Eigen::Vector3f u_next = (v[i + 2] - v[i + 1]).normalized();
    if (d[i + 1] > 0.0f) {
      appendCorner(b, v[i + 1], v[i + 1] + d[i + 1] * u_next, step_m, i + 1, out);
    } else if (turnAngle(u, u_next) > kStraightTurnRad) {
      out.back().stop = true;
    }
  }
  return out;
}

/// Speeds per point: limits, then forward and backward passes (from and to rest).
std::vector<float> speedProfile(const std::vector<GeoPoint>& g, const TrajectoryLimits& limits) {
  const std::size_t n = g.size();
  std::vector<float> v(n, limits.v_max_mps);
  for (std::size_t k = 0; k < n; ++k) {
    if (g[k].curvature > 0.0f) v[k] = std::min(v[k], std::sqrt(limits.a_max_mps2 / g[k].curvature));
    if (g[k].stop) v[k] = 0.0f;
  }
  v.front() = v.back() = 0.0f;
  const float two_a = 2.0f * limits.a_max_mps2;
  for (std::size_t k = 1; k < n; ++k) {
    const float ds = (g[k].p_W - g[k - 1].p_W).norm();
    v[k] = std::min(v[k], std::sqrt(v[k - 1] * v[k - 1] + two_a * ds));
  }
  for (std::size_t k = n - 1; k-- > 0;) {
    const float ds = (g[k + 1].p_W - g[k].p_W).norm();
    v[k] = std::min(v[k], std::sqrt(v[k + 1] * v[k + 1] + two_a * ds));
  }
  return v;
}

Trajectory timeGeometry(const std::vector<GeoPoint>& g, const TrajectoryLimits& limits) {
  const std::vector<float> v = speedProfile(g, limits);
  Trajectory out;
  double t_s = 0.0;
  for (std::size_t k = 0; k < g.size(); ++k) {
    if (k > 0) {
      const float ds = (g[k].p_W - g[k - 1].p_W).norm();
      t_s += 2.0 * ds / std::max(1e-9f, v[k - 1] + v[k]);
    }
    // Tangential acceleration of the interval after the point (before it, at the end; none for
    // a single point).
    float a_t = 0.0f;
    if (g.size() > 1) {
      const std::size_t j = k + 1 < g.size() ? k : k - 1;
      const float ds = std::max(1e-9f, (g[j + 1].p_W - g[j].p_W).norm());
      a_t = (v[j + 1] * v[j + 1] - v[j] * v[j]) / (2.0f * ds);
    }
    TrajectorySample s;
    s.t_s = t_s;
    s.p_W = g[k].p_W;
    s.v_W = v[k] * g[k].tangent;
    s.a_W = a_t * g[k].tangent + v[k] * v[k] * g[k].curvature * g[k].normal;
    out.max_speed_mps = std::max(out.max_speed_mps, v[k]);
    out.max_acceleration_mps2 = std::max(out.max_acceleration_mps2, s.a_W.norm());
    out.samples.push_back(s);
  }
  out.duration_s = t_s;
  return out;
}

/// Vertices whose rounding touches a colliding capsule between consecutive samples (one batch);
/// `free` says whether there were none.
std::set<int> collidingVertices(const std::vector<GeoPoint>& g, CollisionChecker& checker,
                                float radius_m, UnknownPolicy unknown, bool* free) {
  std::vector<EsdfSegment> segments;
  for (std::size_t k = 1; k < g.size(); ++k) segments.push_back({g[k - 1].p_W, g[k].p_W});
  if (segments.empty()) segments.push_back({g[0].p_W, g[0].p_W});
  const std::vector<std::uint8_t> flags = checker.segmentsFree(segments, radius_m, unknown);
  std::set<int> out;
  *free = true;
  for (std::size_t k = 0; k < flags.size(); ++k) {
    if (flags[k] != 0) continue;
    *free = false;
    const std::size_t e = std::min(k + 1, g.size() - 1);
    for (const GeoPoint* p : {&g[k], &g[e]}) out.insert({p->blame_a, p->blame_b});
  }
  return out;
}

/// Initial corner cuts: half of each adjacent segment at most, and a corner deviation at most the
/// clearance margin at the vertex (ESDF distance minus radius; one batch for all vertices).
std::vector<float> initialCuts(const std::vector<Eigen::Vector3f>& v, CollisionChecker& checker,
                               float radius_m) {
  std::vector<float> d(v.size(), 0.0f);
  if (v.size() < 3) return d;
  const std::vector<EsdfSample> samples = checker.sample(v);
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const Eigen::Vector3f in = v[i] - v[i - 1], out = v[i + 1] - v[i];
    const float turn = turnAngle(in.normalized(), out.normalized());
    if (turn <= kStraightTurnRad) continue;
    const float clearance = samples[i].status == EsdfStatus::kKnown ? samples[i].distance_m : 0.0f;
    const float margin = std::max(0.0f, clearance - radius_m);
    d[i] = std::min({0.5f * in.norm(), 0.5f * out.norm(), 2.0f * margin / std::sin(0.5f * turn)});
  }
  return d;
}

}  // namespace

void TrajectoryLimits::validate() const {
  if (!(v_max_mps > 0.0f) || !std::isfinite(v_max_mps)) {
    throw InputError("TrajectoryLimits: v_max_mps must be finite and > 0");
  }
  if (!(a_max_mps2 > 0.0f) || !std::isfinite(a_max_mps2)) {
    throw InputError("TrajectoryLimits: a_max_mps2 must be finite and > 0");
  }
  if (!(sample_step_m >= 0.0f) || !std::isfinite(sample_step_m)) {
    throw InputError("TrajectoryLimits: sample_step_m must be finite and >= 0");
  }
  if (corner_retries < 0) throw InputError("TrajectoryLimits: corner_retries must be >= 0");
}

TrajectorySample Trajectory::at(double t_s) const {
  if (samples.empty()) return {};
  if (t_s <= samples.front().t_s) return samples.front();
  if (t_s >= samples.back().t_s) return samples.back();
  const auto next = std::upper_bound(samples.begin(), samples.end(), t_s,
                                     [](double t, const TrajectorySample& s) { return t < s.t_s; });
  const TrajectorySample& a = *(next - 1);
  const TrajectorySample& b = *next;
  const auto w = static_cast<float>((t_s - a.t_s) / std::max(1e-12, b.t_s - a.t_s));
  TrajectorySample out;
  out.t_s = t_s;
  out.p_W = a.p_W + w * (b.p_W - a.p_W);
  out.v_W = a.v_W + w * (b.v_W - a.v_W);
  out.a_W = a.a_W + w * (b.a_W - a.a_W);
  return out;
}

Trajectory makeTrajectory(const std::vector<Eigen::Vector3f>& path_W,
                          const TrajectoryLimits& limits, CollisionChecker& checker, float radius_m,
                          UnknownPolicy unknown) {
  limits.validate();
  if (!(radius_m >= 0.0f) || !std::isfinite(radius_m)) {
    throw InputError("makeTrajectory: radius_m must be finite and >= 0");
  }
  const std::vector<Eigen::Vector3f> v = dropRepeats(path_W);
  if (v.empty()) throw InputError("makeTrajectory: the path is empty");
  const float step_m =
      limits.sample_step_m > 0.0f ? limits.sample_step_m : 0.5f * checker.voxelSize();
  std::vector<float> d = initialCuts(v, checker, radius_m);
  std::vector<int> halvings(v.size(), 0);
  for (;;) {
    const std::vector<GeoPoint> g = buildGeometry(v, d, step_m);
    bool free = false;
    const std::set<int> colliding = collidingVertices(g, checker, radius_m, unknown, &free);
    bool changed = false;
    for (const int i : colliding) {
      if (d[i] == 0.0f) continue;
      // Below a quarter step a curve is no longer resolved by the samples: leave it sharp.
      d[i] = ++halvings[i] > limits.corner_retries || d[i] < 0.5f * step_m ? 0.0f : 0.5f * d[i];
      changed = true;
    }
    if (changed) continue;
    Trajectory out = timeGeometry(g, limits);
    out.collision_free = free;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      const float turn = turnAngle((v[i] - v[i - 1]).normalized(), (v[i + 1] - v[i]).normalized());
      out.corner_deviation_m.push_back(0.5f * d[i] * std::sin(0.5f * turn));
    }
    return out;
  }
}

}  // namespace strata::plan
