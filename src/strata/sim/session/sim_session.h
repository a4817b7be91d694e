#pragma once
// One simulated mapping session as a Dataset: frames rendered on demand in memory (no disk), the
// exact poses kept beside the poses given to the mapper (optionally drifted, or an odometry's).
// Thread safety: load()/render() may be called from several threads at once.
#include <memory>
#include <optional>
#include <vector>

#include "strata/io/open_dataset.h"
#include "strata/sim/sensors/imu.h"
#include "strata/sim/sensors/odometry_drift.h"
#include "strata/sim/sensors/rgbd_camera.h"
#include "strata/sim/sensors/camera_path.h"
#include "strata/sim/session/session_path.h"
#include "strata/sim/world/world.h"

namespace strata::sim {

struct SimSessionConfig {
  RgbdCameraConfig camera;
  /// Frames per second of the recording along the trajectory.
  double frame_rate_hz = 30.0;
  /// > 0: keep this many frames spread evenly over the trajectory (keyframe-like; fast demos).
  int max_frames = 0;
  TrajectoryConfig trajectory;
  SessionPathConfig path;
  /// Add odometry drift to the poses given to the mapper (the truth is kept).
  bool drift = false;
  DriftConfig drift_config;
  /// Seeds noise, path jitter and drift; 0 = derived from the world's seed.
  std::uint64_t seed = 0;

  void validate() const;
};

class SimSessionDataset : public Dataset {
 public:
  SimSessionDataset(std::shared_ptr<const World> world, int session,
                    const SimSessionConfig& config = {});
  ~SimSessionDataset() override;

  std::string name() const override;
  std::size_t size() const override { return times_s_.size(); }
  /// Frames of the full recording at frame_rate_hz (size() when max_frames keeps them all).
  std::size_t recordedFrames() const { return recorded_frames_; }
  CameraIntrinsics intrinsics() const override { return config_.camera.intrinsics; }
  /// The sensor frame with the pose given to the mapper (drifted when configured).
  RgbdFrame load(std::size_t index) const override;
  /// The given pose and time of a frame, without rendering it.
  FrameStamp stamp(std::size_t index) const override;
  /// Everything the sensor saw, with ground truth (exact depth, object ids).
  SimulatedFrame render(std::size_t index) const;

  int session() const { return session_; }
  const World& world() const { return *world_; }
  const WorldScene& scene() const { return *scene_; }
  const Trajectory& trajectory() const { return *trajectory_; }
  double timestamp(std::size_t index) const { return times_s_.at(index); }
  const std::vector<Eigen::Isometry3d>& truePoses() const { return true_T_W_C_; }
  const std::vector<Eigen::Isometry3d>& givenPoses() const { return given_T_W_C_; }
  /// Replaces the poses given to the mapper by others (e.g. an odometry's), one per frame; a frame
  /// given none (nullopt) is dropped: size(), timestamp(), truePoses() and givenPoses() then hold
  /// the kept frames only, and each kept frame renders as before (same noise). Call before the
  /// frames are used (not thread safe). Throws InputError when the count is not size().
  void replaceGivenPoses(const std::vector<std::optional<Eigen::Isometry3d>>& T_W_C);
  /// The session's lighting and seed (what its sensors render and draw with).
  const Lighting& lighting() const { return lighting_; }
  std::uint64_t seed() const { return seed_; }
  /// IMU samples over the whole trajectory (EuRoC rates and noise by default).
  std::vector<ImuSample> imu(const ImuConfig& config = {}) const;

 private:
  std::shared_ptr<const World> world_;
  int session_;
  SimSessionConfig config_;
  std::uint64_t seed_;
  std::unique_ptr<WorldScene> scene_;
  std::unique_ptr<Trajectory> trajectory_;
  std::unique_ptr<RgbdCamera> camera_;
  Lighting lighting_;
  std::vector<double> times_s_;
  // Per frame: its index before replaceGivenPoses (its noise seed and name).
  std::vector<std::size_t> frame_number_;
  std::size_t recorded_frames_ = 0;
  std::vector<Eigen::Isometry3d> true_T_W_C_;
  std::vector<Eigen::Isometry3d> given_T_W_C_;
};

}  // namespace strata::sim
