// The exploration loop's pieces apart from the loop itself: its config, the camera, the start
// clearing, and the construction of the mapper.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "strata/core/error.h"
#include "strata/explore/exploration_loop.h"
#include "strata/explore/internal/loop_impl.h"

namespace strata::explore {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

/// Observed free space (tsdf = +truncation, a small weight that real observations soon outweigh)
/// at the voxels of the start cylinder whose centres are at least half a voxel diagonal from
/// every solid in truth; the others stay unknown.
TsdfMap startClearing(const MapConfig& map_config, const sim::WorldScene& scene,
                      const Eigen::Vector3f& start_W, float radius_m, float half_height_m) {
  TsdfMap map(map_config);
  const float voxel = map_config.voxel_size_m;
  const float margin = 0.5f * std::sqrt(3.0f) * voxel;
  const Eigen::Vector3f reach(radius_m, radius_m, half_height_m);
  const Eigen::Vector3i lo = ((start_W - reach) / voxel).array().floor().cast<int>();
  const Eigen::Vector3i hi = ((start_W + reach) / voxel).array().floor().cast<int>();
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) {
        const Eigen::Vector3f c = voxelCenter(Eigen::Vector3i(x, y, z), voxel);
        if ((c - start_W).head<2>().norm() > radius_m) continue;
        if (std::abs(c.z() - start_W.z()) > half_height_m) continue;
        if (!(scene.signedDistance(c) > margin)) continue;
        TsdfVoxel& v = map.allocateVoxel(Eigen::Vector3i(x, y, z));
        v.tsdf_m = map_config.truncationDistance();
        v.weight = 0.01f;
      }
    }
  }
  return map;
}

void requireClearStart(const sim::WorldScene& scene, const Eigen::Vector3f& start_W,
                       const ExplorationConfig& c) {
  const float needed = startClearanceNeeded(c);
  const float clearance = scene.signedDistance(start_W);
  if (!(clearance >= needed)) {
    throw InputError("start (" + std::to_string(start_W.x()) + ", " + std::to_string(start_W.y()) +
                     ", " + std::to_string(start_W.z()) + ") is " + std::to_string(clearance) +
                     " m from the nearest surface; " + "it needs " + std::to_string(needed) + " m");
  }
}

}  // namespace

float startClearanceNeeded(const ExplorationConfig& config) { return config.checkRadius() + 0.2f; }

float defaultVoxelSize(const sim::World& world) {
  const double fine = kFineVoxelM;
  const double voxels = world.bounds().sizes().prod() / (fine * fine * fine);
  return voxels <= kFineVoxelBudget ? kFineVoxelM : kCoarseVoxelM;
}

Eigen::Vector3f defaultStart(const sim::World& world, float height_m,
                             const ExplorationConfig& config) {
  const sim::RoomSpec& room = world.spec().rooms.front();
  const std::unique_ptr<sim::WorldScene> scene = world.buildScene(0);
  const Eigen::Vector2f centre = (0.5 * (room.min_m + room.max_m)).cast<float>();
  const float needed = startClearanceNeeded(config);
  Eigen::Vector3f best = Eigen::Vector3f::Constant(std::nanf(""));
  float best_d = std::numeric_limits<float>::infinity();
  constexpr float kStep = 0.1f;
  for (double x = room.min_m.x(); x <= room.max_m.x(); x += kStep) {
    for (double y = room.min_m.y(); y <= room.max_m.y(); y += kStep) {
      const Eigen::Vector3f p(static_cast<float>(x), static_cast<float>(y), height_m);
      const float d = (p.head<2>() - centre).norm();
      if (d >= best_d || !(scene->signedDistance(p) >= needed)) continue;
      best = p;
      best_d = d;
    }
  }
  if (!best.allFinite()) {
    throw InputError("no start in room '" + room.name + "' at height " + std::to_string(height_m) +
                     " m is " + std::to_string(needed) + " m from every surface; give --start");
  }
  return best;
}

ViewGainConfig ExplorationConfig::coarseGain() {
  ViewGainConfig g;
  g.yaw_bins = 36;
  g.rays_per_bin = 1;
  g.elevation_rays = 8;
  // The nodding camera's two frames (camera_pitch_rad = 0.41 rad, 46.8 degrees each).
  g.vertical_fov_rad = 1.636f;
  return g;
}

float ExplorationConfig::checkRadius() const {
  return robot.radius_m + std::max(collision_margin_m, kMarginVoxels * voxel_size_m);
}

void ExplorationConfig::validate() const {
  robot.validate();
  gain.validate();
  if (!(collision_margin_m >= 0.0f)) throw InputError("collision_margin_m must be >= 0");
  if (!positive(voxel_size_m)) throw InputError("voxel size must be > 0");
  if (camera_width_px < 8 || camera_height_px < 8) throw InputError("camera image too small");
  if (!positive(camera_min_range_m) || !(camera_max_range_m > camera_min_range_m)) {
    throw InputError("camera ranges: need 0 < min < max");
  }
  for (double v : {camera_rate_hz, replan_period_s, time_limit_s, eval_period_s, motion_step_s}) {
    if (!positive(v)) throw InputError("exploration rates, periods and time limit must be > 0");
  }
  if (!(target_fraction > 0.0 && target_fraction <= 1.0)) {
    throw InputError("target fraction must be in (0, 1]");
  }
  if (!positive(start_clearing_radius_m) || !positive(start_clearing_half_height_m)) {
    throw InputError("start clearing sizes must be > 0");
  }
  if (max_idle_steps < 1) throw InputError("max_idle_steps must be >= 1");
  if (!(camera_pitch_rad >= 0.0f && camera_pitch_rad < 1.2f)) {
    throw InputError("camera_pitch_rad must be in [0, 1.2) rad");
  }
  if (!positive(inflight_lookahead_m)) throw InputError("inflight_lookahead_m must be > 0");
}

float framePitch(const ExplorationConfig& config, std::uint64_t index) {
  return index % 2 == 0 ? config.camera_pitch_rad : -config.camera_pitch_rad;
}

Eigen::Isometry3d cameraPose(const RobotPose& pose, float pitch_rad) {
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  const double cp = std::cos(pitch_rad), sp = std::sin(pitch_rad);
  const Eigen::Vector3d forward(c, s, 0.0), up(0.0, 0.0, 1.0);
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(s, -c, 0.0);   // image x: to the right of the heading
  R.col(1) = -cp * up + sp * forward;       // image y: down, tilted with the pitch
  R.col(2) = cp * forward + sp * up;        // optical axis: the heading, pitched
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = pose.position_W.cast<double>();
  return T;
}

sim::RgbdCameraConfig cameraConfig(const ExplorationConfig& c) {
  sim::RgbdCameraConfig camera;
  const float f = 0.5f * c.camera_width_px / std::tan(0.5f * c.gain.horizontal_fov_rad);
  camera.intrinsics = {c.camera_width_px,
                       c.camera_height_px,
                       f,
                       f,
                       0.5f * (c.camera_width_px - 1),
                       0.5f * (c.camera_height_px - 1)};
  camera.min_range_m = c.camera_min_range_m;
  camera.max_range_m = c.camera_max_range_m;
  return camera;
}

SurfaceHitsConfig surfaceHitsConfig(const ExplorationConfig& c) {
  SurfaceHitsConfig h;
  h.max_depth_m = c.camera_max_range_m;  // endpoints as far as the map fuses them
  return h;
}

MapperConfig mapperConfig(const ExplorationConfig& c) {
  MapperConfig m;
  m.map.voxel_size_m = c.voxel_size_m;
  m.map.min_depth_m = c.camera_min_range_m;
  m.map.max_depth_m = c.camera_max_range_m;
  m.map.allocate_free_space = true;
  m.esdf = true;
  m.esdf_config.min_weight = c.gain.min_weight;
  m.change_detection = false;
  return m;
}

ExplorationLoop::ExplorationLoop(const sim::World& world, const ExplorationTruth& truth,
                                 const ExplorationConfig& config, const RobotPose& start,
                                 vk::Context& context)
    : world_(world), truth_(truth), config_(config), start_(start), context_(context) {
  config_.validate();
  const Eigen::AlignedBox3d b = world.bounds();
  const Eigen::Vector3f margin = Eigen::Vector3f::Constant(config_.robot.radius_m);
  bounds_W_ = Eigen::AlignedBox3f(b.min().cast<float>() + margin, b.max().cast<float>() - margin);
  requireClearStart(truth.scene(), start.position_W, config_);
  const MapperConfig mapper_config = mapperConfig(config_);
  mapper_ = Mapper::fromMap(
      startClearing(mapper_config.map, truth.scene(), start.position_W,
                    config_.start_clearing_radius_m, config_.start_clearing_half_height_m),
      context, mapper_config);
  impl_ = std::make_unique<Impl>(config_, world, start, context);
}

ExplorationLoop::~ExplorationLoop() = default;

}  // namespace strata::explore
