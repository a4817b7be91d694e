#include "strata/align/internal/dense_icp.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace strata::align::detail {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Normals from depth differences this many pixels apart: one pixel is dominated by the sensor's
// depth noise and quantisation; two keeps thin structures.
constexpr int kNormalStepPx = 4;
// Neighbours farther than this from the centre (relative to its depth) lie across an edge.
constexpr float kMaxRelativeDepthJump = 0.05f;
// Fewer correspondences than this cannot constrain six degrees of freedom reliably.
constexpr int kMinCorrespondences = 100;
constexpr double kConvergedStep = 1e-6;
// The association gate halves every iteration from the configured one down to this: the wide
// gate pulls in a pose that is centimetres off, the narrow one keeps depth noise and edges far
// from the plane out of the final estimate.
constexpr double kFinestGate_m = 0.01;

// Camera-frame points of a depth image, NaN where the depth is missing.
struct VertexImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<Eigen::Vector3f> points_C_m;

  const Eigen::Vector3f& at(int u, int v) const {
    return points_C_m[static_cast<std::size_t>(v) * width_px + u];
  }
};

VertexImage vertices(const DepthImage& depth, const CameraIntrinsics& intrinsics) {
  VertexImage image{depth.width_px, depth.height_px, {}};
  image.points_C_m.resize(depth.depth_m.size(), Eigen::Vector3f::Constant(NAN));
  for (int v = 0; v < depth.height_px; ++v) {
    for (int u = 0; u < depth.width_px; ++u) {
      const float z_m = depth.at(u, v);
      if (!(z_m > 0.0f) || !std::isfinite(z_m)) continue;
      image.points_C_m[static_cast<std::size_t>(v) * depth.width_px + u] = {
          (u - intrinsics.cx_px) / intrinsics.fx_px * z_m,
          (v - intrinsics.cy_px) / intrinsics.fy_px * z_m, z_m};
    }
  }
  return image;
}

// Unit normal at (u, v) facing the camera; false at the border, holes and depth edges.
bool normalAt(const VertexImage& image, int u, int v, Eigen::Vector3f& normal) {
  constexpr int s = kNormalStepPx;
  if (u < s || v < s || u + s >= image.width_px || v + s >= image.height_px) return false;
  const Eigen::Vector3f& centre = image.at(u, v);
  if (!std::isfinite(centre.z())) return false;  // a hole: no vertex to associate with
  const Eigen::Vector3f* around[4] = {&image.at(u - s, v), &image.at(u + s, v), &image.at(u, v - s),
                                      &image.at(u, v + s)};
  for (const Eigen::Vector3f* p : around) {
    if (!std::isfinite(p->z()) ||
        std::abs(p->z() - centre.z()) > kMaxRelativeDepthJump * centre.z())
      return false;
  }
  normal = (*around[1] - *around[0]).cross(*around[3] - *around[2]);
  const float length = normal.norm();
  if (!(length > 0.0f)) return false;
  normal /= length;
  if (normal.dot(centre) > 0.0f) normal = -normal;
  return true;
}

// A subsampled pixel of b with its point and normal in b's camera frame.
struct SamplePoint {
  Eigen::Vector3d p_b;
  Eigen::Vector3d n_b;
};

std::vector<SamplePoint> samples(const VertexImage& b, int stride_px, int& valid) {
  std::vector<SamplePoint> out;
  valid = 0;
  for (int v = 0; v < b.height_px; v += stride_px) {
    for (int u = 0; u < b.width_px; u += stride_px) {
      if (!std::isfinite(b.at(u, v).z())) continue;
      ++valid;
      Eigen::Vector3f n;
      if (normalAt(b, u, v, n)) out.push_back({b.at(u, v).cast<double>(), n.cast<double>()});
    }
  }
  return out;
}

struct NormalEquations {
  store::Matrix6d JtJ = store::Matrix6d::Zero();
  Vector6d Jtr = Vector6d::Zero();
  double sum_squares = 0.0;
  int count = 0;
};

// Projective association of every sample at T_a_b and the point-to-plane normal equations.
NormalEquations associate(const std::vector<SamplePoint>& points_b, const VertexImage& a,
                          const CameraIntrinsics& intrinsics_a, const Eigen::Isometry3d& T_a_b,
                          const DenseIcpConfig& config) {
  NormalEquations eq;
  const Eigen::Matrix3d R = T_a_b.linear();
  const double min_cos = std::cos(config.max_normal_angle_rad);
  for (const SamplePoint& s : points_b) {
    const Eigen::Vector3d q = T_a_b * s.p_b;
    if (!(q.z() > 0.0)) continue;
    const int u =
        static_cast<int>(std::lround(intrinsics_a.fx_px * q.x() / q.z() + intrinsics_a.cx_px));
    const int v =
        static_cast<int>(std::lround(intrinsics_a.fy_px * q.y() / q.z() + intrinsics_a.cy_px));
    if (u < 0 || v < 0 || u >= a.width_px || v >= a.height_px) continue;
    Eigen::Vector3f n_a_f;
    if (!normalAt(a, u, v, n_a_f)) continue;
    const Eigen::Vector3d n_a = n_a_f.cast<double>();
    const Eigen::Vector3d d = q - a.at(u, v).cast<double>();
    if (!d.allFinite() || !n_a.allFinite()) continue;  // a pixel without depth has no vertex
    if (d.norm() > config.max_distance_m || n_a.dot(R * s.n_b) < min_cos) continue;
    const double r = n_a.dot(d);
    // d r / d delta for T_a_b * Exp(delta): translation R^T n_a, rotation p_b x (R^T n_a).
    const Eigen::Vector3d m = R.transpose() * n_a;
    Vector6d J;
    J << m, s.p_b.cross(m);
    eq.JtJ.noalias() += J * J.transpose();
    eq.Jtr += J * r;
    eq.sum_squares += r * r;
    ++eq.count;
  }
  return eq;
}

Eigen::Isometry3d expRight(const Vector6d& delta) {
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w = delta.tail<3>();
  const double angle = w.norm();
  if (angle > 0.0) D.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  D.translation() = delta.head<3>();
  return D;
}

}  // namespace

DenseIcpResult denseIcp(const DepthImage& depth_a, const CameraIntrinsics& intrinsics_a,
                        const DepthImage& depth_b, const CameraIntrinsics& intrinsics_b,
                        const Eigen::Isometry3d& T_a_b_initial, const DenseIcpConfig& config) {
  DenseIcpResult result;
  result.T_a_b = T_a_b_initial;
  const VertexImage a = vertices(depth_a, intrinsics_a);
  const std::vector<SamplePoint> points_b =
      samples(vertices(depth_b, intrinsics_b), config.stride_px, result.valid_b);

  DenseIcpConfig step = config;
  for (int iteration = 0; iteration < config.iterations; ++iteration) {
    step.max_distance_m = std::max(std::min(kFinestGate_m, config.max_distance_m),
                                   config.max_distance_m * std::pow(0.5, iteration));
    const NormalEquations eq = associate(points_b, a, intrinsics_a, result.T_a_b, step);
    if (eq.count < kMinCorrespondences) return result;
    const Eigen::LDLT<store::Matrix6d> solver(eq.JtJ);
    if (solver.info() != Eigen::Success || !solver.isPositive()) return result;
    const Vector6d delta = -solver.solve(eq.Jtr);
    if (!delta.allFinite()) return result;
    result.T_a_b = result.T_a_b * expRight(delta);
    if (delta.norm() < kConvergedStep && step.max_distance_m <= kFinestGate_m) break;
  }
  const NormalEquations eq = associate(points_b, a, intrinsics_a, result.T_a_b, config);
  if (eq.count < kMinCorrespondences) return result;
  result.converged = true;
  result.inliers = eq.count;
  result.rms_m = std::sqrt(eq.sum_squares / eq.count);
  result.JtJ = eq.JtJ;
  return result;
}

}  // namespace strata::align::detail
