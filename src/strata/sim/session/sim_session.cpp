#include "strata/sim/session/sim_session.h"

#include <cmath>
#include <cstdio>

#include "strata/core/error.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

Lighting lightingOf(const SessionTruth& truth) {
  Lighting lighting;
  lighting.direction_W = truth.light.direction_W.normalized();
  lighting.intensity = truth.light.intensity;
  lighting.ambient = truth.light.ambient;
  return lighting;
}

/// Times k / rate over the trajectory, or max_frames of them spread evenly.
std::vector<double> frameTimes(const Trajectory& trajectory, const SimSessionConfig& config) {
  std::vector<double> times = trajectory.sampleTimes(config.frame_rate_hz);
  if (config.max_frames <= 0 || static_cast<int>(times.size()) <= config.max_frames) return times;
  std::vector<double> kept;
  kept.reserve(static_cast<std::size_t>(config.max_frames));
  const double step = static_cast<double>(times.size() - 1) / (config.max_frames - 1);
  for (int k = 0; k < config.max_frames; ++k) {
    kept.push_back(times[static_cast<std::size_t>(std::lround(k * step))]);
  }
  return kept;
}

}  // namespace

void SimSessionConfig::validate() const {
  camera.validate();
  trajectory.validate();
  if (!std::isfinite(frame_rate_hz) || frame_rate_hz <= 0.0) {
    throw InputError("simulated session: frame_rate_hz must be positive");
  }
  if (max_frames == 1) throw InputError("simulated session: max_frames must be 0 or >= 2");
  if (drift) drift_config.validate();
}

SimSessionDataset::SimSessionDataset(std::shared_ptr<const World> world, int session,
                                     const SimSessionConfig& config)
    : world_(std::move(world)), session_(session), config_(config) {
  config_.validate();
  const SessionTruth& truth = world_->session(session);  // throws for a bad index
  seed_ = hashCombine(config_.seed != 0 ? config_.seed : world_->seed(), 0x53455353ull,
                      static_cast<std::uint64_t>(session));
  scene_ = world_->buildScene(session);
  trajectory_ = std::make_unique<Trajectory>(
      sessionTrajectory(*world_, session, *scene_, config_.path, config_.trajectory, seed_));
  camera_ = std::make_unique<RgbdCamera>(config_.camera);
  lighting_ = lightingOf(truth);
  recorded_frames_ = trajectory_->sampleTimes(config_.frame_rate_hz).size();
  times_s_ = frameTimes(*trajectory_, config_);
  for (std::size_t i = 0; i < times_s_.size(); ++i) {
    true_T_W_C_.push_back(trajectory_->pose(times_s_[i]));
    frame_number_.push_back(i);
  }
  given_T_W_C_ = config_.drift ? addOdometryDrift(true_T_W_C_, config_.drift_config, seed_)
                               : true_T_W_C_;
}

SimSessionDataset::~SimSessionDataset() = default;

std::string SimSessionDataset::name() const {
  return "world '" + world_->name() + "' session " + std::to_string(session_);
}

SimulatedFrame SimSessionDataset::render(std::size_t index) const {
  if (index >= times_s_.size()) {
    throw InputError(name() + ": frame " + std::to_string(index) + " out of range (" +
                     std::to_string(times_s_.size()) + " frames)");
  }
  return camera_->render(*scene_, true_T_W_C_[index], lighting_,
                         hashCombine(seed_, frame_number_[index]));
}

void SimSessionDataset::replaceGivenPoses(
    const std::vector<std::optional<Eigen::Isometry3d>>& T_W_C) {
  if (T_W_C.size() != times_s_.size()) {
    throw InputError(name() + ": " + std::to_string(T_W_C.size()) + " poses given for " +
                     std::to_string(times_s_.size()) + " frames");
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < T_W_C.size(); ++i) {
    if (!T_W_C[i]) continue;
    times_s_[kept] = times_s_[i];
    frame_number_[kept] = frame_number_[i];
    true_T_W_C_[kept] = true_T_W_C_[i];
    given_T_W_C_[kept] = *T_W_C[i];
    ++kept;
  }
  times_s_.resize(kept);
  frame_number_.resize(kept);
  true_T_W_C_.resize(kept);
  given_T_W_C_.resize(kept);
}

RgbdFrame SimSessionDataset::load(std::size_t index) const {
  SimulatedFrame frame = render(index);  // throws for an index out of range
  char frame_name[64];
  std::snprintf(frame_name, sizeof(frame_name), "session %d frame %zu", session_,
                frame_number_[index]);
  return makeRgbdFrame(std::move(frame), given_T_W_C_[index], times_s_[index], frame_name);
}

FrameStamp SimSessionDataset::stamp(std::size_t index) const {
  if (index >= times_s_.size()) return Dataset::stamp(index);  // load() names the error
  return {times_s_[index], given_T_W_C_[index]};
}

std::vector<ImuSample> SimSessionDataset::imu(const ImuConfig& config) const {
  return simulateImu(*trajectory_, config, hashCombine(seed_, 0x494d55ull));
}

}  // namespace strata::sim
