#include "strata/sim/analytic_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "strata/core/error.h"

namespace strata::sim {
namespace {

// Lambert shading: light from above and behind the usual viewpoints, plus ambient.
const Eigen::Vector3d kLightDirection_W = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();
constexpr double kAmbient = 0.35;

std::array<std::uint8_t, 3> shade(const AnalyticHit& hit) {
  const double lambert = std::max(0.0, hit.normal_W.dot(kLightDirection_W));
  const double factor = kAmbient + (1.0 - kAmbient) * lambert;
  std::array<std::uint8_t, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    rgb[c] = static_cast<std::uint8_t>(std::lround(std::min(255.0, hit.albedo[c] * factor)));
  }
  return rgb;
}

template <typename Primitive>
void closestHit(const std::vector<Primitive>& primitives, const Eigen::Vector3d& origin_W,
                const Eigen::Vector3d& dir_W, double* max_t_m, AnalyticHit* best, bool* found) {
  for (const Primitive& primitive : primitives) {
    const std::optional<SurfaceHit> hit = intersect(primitive, origin_W, dir_W, *max_t_m);
    if (!hit) continue;
    *max_t_m = hit->t_m;
    *best = AnalyticHit{hit->t_m, hit->normal_W, primitive.albedo};
    *found = true;
  }
}

template <typename Primitive>
double minDistance(const std::vector<Primitive>& primitives, const Eigen::Vector3d& p_W,
                   double distance) {
  for (const Primitive& primitive : primitives) {
    distance = std::min(distance, strata::sim::signedDistance(primitive, p_W));
  }
  return distance;
}

}  // namespace

void AnalyticScene::add(Plane plane) {
  const double norm = plane.normal_W.norm();
  if (!std::isfinite(norm) || norm < 1e-12 || !plane.point_W.allFinite()) {
    throw InputError("AnalyticScene: plane needs a finite point and a non-zero normal");
  }
  plane.normal_W /= norm;
  planes_.push_back(plane);
}

void AnalyticScene::add(const Box& box) {
  const Eigen::Matrix3d& R = box.R_W_B;
  const bool rotation = R.allFinite() &&
                        (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
                        R.determinant() > 0.0;
  if (!box.centre_W.allFinite() || !(box.half_extents_m.minCoeff() > 0.0) || !rotation) {
    throw InputError(
        "AnalyticScene: box needs a finite centre, positive half extents and a "
        "rotation R_W_B");
  }
  boxes_.push_back(box);
}

void AnalyticScene::add(const Sphere& sphere) {
  if (!sphere.centre_W.allFinite() || !(sphere.radius_m > 0.0) || !std::isfinite(sphere.radius_m)) {
    throw InputError("AnalyticScene: sphere needs a finite centre and a positive radius");
  }
  spheres_.push_back(sphere);
}

double AnalyticScene::signedDistance(const Eigen::Vector3d& p_W) const {
  double distance = std::numeric_limits<double>::infinity();
  distance = minDistance(planes_, p_W, distance);
  distance = minDistance(boxes_, p_W, distance);
  return minDistance(spheres_, p_W, distance);
}

float AnalyticScene::signedDistance(const Eigen::Vector3f& p_W) const {
  return static_cast<float>(signedDistance(Eigen::Vector3d(p_W.cast<double>())));
}

bool AnalyticScene::castRay(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& unit_dir_W,
                            double max_t_m, AnalyticHit* hit) const {
  AnalyticHit best;
  bool found = false;
  closestHit(planes_, origin_W, unit_dir_W, &max_t_m, &best, &found);
  closestHit(boxes_, origin_W, unit_dir_W, &max_t_m, &best, &found);
  closestHit(spheres_, origin_W, unit_dir_W, &max_t_m, &best, &found);
  if (found && hit != nullptr) *hit = best;
  return found;
}

void AnalyticScene::render(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_C,
                           float max_depth_m, DepthImage* depth, ColorImage* color) const {
  intrinsics.validate();
  const int width = intrinsics.width_px;
  const int height = intrinsics.height_px;
  if (depth != nullptr) *depth = DepthImage(width, height);
  if (color != nullptr) *color = ColorImage(width, height);
  const Eigen::Matrix3d R_W_C = T_W_C.linear();
  const Eigen::Vector3d origin_W = T_W_C.translation();
  const double fx = intrinsics.fx_px, fy = intrinsics.fy_px;
  const double cx = intrinsics.cx_px, cy = intrinsics.cy_px;
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const Eigen::Vector3d ray_C((u - cx) / fx, (v - cy) / fy, 1.0);
      const double length = ray_C.norm();  // metres along the ray per metre of depth
      AnalyticHit hit;
      if (!castRay(origin_W, R_W_C * ray_C / length, max_depth_m * length, &hit)) continue;
      if (depth != nullptr) depth->at(u, v) = static_cast<float>(hit.t_m / length);
      if (color != nullptr) {
        const std::array<std::uint8_t, 3> rgb = shade(hit);
        const std::size_t offset = (static_cast<std::size_t>(v) * width + u) * 3;
        std::copy(rgb.begin(), rgb.end(), color->rgb.begin() + offset);
      }
    }
  }
}

DepthImage AnalyticScene::renderDepth(const CameraIntrinsics& intrinsics,
                                      const Eigen::Isometry3d& T_W_C, float max_depth_m) const {
  DepthImage depth;
  render(intrinsics, T_W_C, max_depth_m, &depth, nullptr);
  return depth;
}

ColorImage AnalyticScene::renderColor(const CameraIntrinsics& intrinsics,
                                      const Eigen::Isometry3d& T_W_C, float max_depth_m) const {
  ColorImage color;
  render(intrinsics, T_W_C, max_depth_m, nullptr, &color);
  return color;
}

}  // namespace strata::sim
