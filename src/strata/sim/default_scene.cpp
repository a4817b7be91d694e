#include "strata/sim/default_scene.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/core/math_constants.h"

namespace strata::sim {
namespace {

constexpr double kWallHeight_m = 2.5;
constexpr double kWallThickness_m = 0.2;
constexpr double kCameraHeight_m = 1.4;
constexpr double kArcRadius_m = 2.0;
constexpr double kArcStart_deg = -100.0;  // angle around the centre, from +x towards +y
constexpr double kArcEnd_deg = 10.0;

/// Box standing on the floor (bottom face on z = 0), turned by yaw about z.
Box restingBox(double x, double y, const Eigen::Vector3d& size_m, double yaw_deg, Albedo albedo) {
  Box box;
  box.half_extents_m = 0.5 * size_m;
  box.centre_W = Eigen::Vector3d(x, y, box.half_extents_m.z());
  box.R_W_B = Eigen::AngleAxisd(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  box.albedo = albedo;
  return box;
}

/// Sphere touching the floor at (x, y, 0).
Sphere restingSphere(double x, double y, double radius_m, Albedo albedo) {
  return Sphere{Eigen::Vector3d(x, y, radius_m), radius_m, albedo};
}

/// Wall box spanning [x0, x1] x [y0, y1] on the floor.
Box wall(double x0, double x1, double y0, double y1, Albedo albedo) {
  Box box;
  box.centre_W = Eigen::Vector3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * kWallHeight_m);
  box.half_extents_m = Eigen::Vector3d(0.5 * (x1 - x0), 0.5 * (y1 - y0), 0.5 * kWallHeight_m);
  box.albedo = albedo;
  return box;
}

}  // namespace

AnalyticScene makeDefaultScene() {
  AnalyticScene scene;
  scene.add(Plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), {150, 150, 150}});
  // Walls touch along the face y = 2 for x in [-2.2, -2.0]; their interiors are disjoint.
  scene.add(wall(-2.0 - kWallThickness_m, -2.0, -2.0, 2.0, {210, 190, 160}));
  scene.add(wall(-2.0 - kWallThickness_m, 2.0, 2.0, 2.0 + kWallThickness_m, {170, 200, 220}));
  scene.add(restingBox(-0.6, 0.6, {0.4, 0.3, 0.4}, 30.0, {200, 40, 40}));
  scene.add(restingBox(0.6, -0.5, {0.5, 0.5, 0.25}, -20.0, {40, 70, 200}));
  scene.add(restingBox(-1.3, 1.3, {0.3, 0.3, 0.6}, 10.0, {240, 140, 30}));
  scene.add(restingSphere(0.5, 0.8, 0.25, {40, 180, 60}));
  scene.add(restingSphere(-0.5, -0.6, 0.15, {230, 210, 40}));
  scene.add(restingSphere(0.0, 0.0, 0.2, {190, 60, 190}));
  return scene;
}

Eigen::Vector3d defaultSceneCentre() { return Eigen::Vector3d(-0.3, 0.3, 0.3); }

Eigen::Isometry3d lookAt(const Eigen::Vector3d& position_W, const Eigen::Vector3d& target_W) {
  const Eigen::Vector3d forward = (target_W - position_W).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (!(right.norm() > 1e-6)) {
    throw InputError("lookAt: the view direction is vertical or degenerate (no image up)");
  }
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  T_W_C.linear().col(0) = right.normalized();                 // x right
  T_W_C.linear().col(1) = forward.cross(right.normalized());  // y down
  T_W_C.linear().col(2) = forward;                            // z forward
  T_W_C.translation() = position_W;
  return T_W_C;
}

std::vector<Eigen::Isometry3d> makeDefaultTrajectory(int frame_count) {
  if (frame_count < 1) {
    throw InputError("makeDefaultTrajectory: frame_count must be >= 1, got " +
                     std::to_string(frame_count));
  }
  const Eigen::Vector3d centre = defaultSceneCentre();
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < frame_count; ++i) {
    const double s = frame_count > 1 ? static_cast<double>(i) / (frame_count - 1) : 0.5;
    const double angle = (kArcStart_deg + s * (kArcEnd_deg - kArcStart_deg)) * kPi / 180.0;
    const Eigen::Vector3d position(centre.x() + kArcRadius_m * std::cos(angle),
                                   centre.y() + kArcRadius_m * std::sin(angle), kCameraHeight_m);
    poses.push_back(lookAt(position, centre));
  }
  return poses;
}

AnalyticRayScene makeStereoTestRoom(int threads) {
  AnalyticRayScene scene(threads);
  using V = Eigen::Vector3d;
  scene.add(Plane{V(0, 0, 0), V(0, 0, 1), {150, 140, 130}});   // floor
  scene.add(Plane{V(0, 0, 3), V(0, 0, -1), {200, 200, 200}});  // ceiling
  scene.add(Plane{V(0, 4, 0), V(0, -1, 0), {180, 170, 160}});
  scene.add(Plane{V(0, -4, 0), V(0, 1, 0), {180, 170, 160}});
  scene.add(Plane{V(3, 0, 0), V(-1, 0, 0), {160, 180, 170}});
  scene.add(Plane{V(-3, 0, 0), V(1, 0, 0), {160, 180, 170}});
  scene.add(Box{V(-0.6, 1.5, 0.5), V(0.3, 0.3, 0.5), Eigen::Matrix3d::Identity(), {90, 110, 200}});
  scene.add(Box{V(0.9, 2.2, 1.2), V(0.4, 0.25, 0.3), Eigen::AngleAxisd(0.5, V::UnitZ()).matrix(),
                {210, 120, 90}});
  return scene;
}

}  // namespace strata::sim
