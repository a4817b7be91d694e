#pragma once
// A simulated session recorded as a grey stereo camera + IMU in the EuRoC/ASL layout
// (io/euroc_dataset.h reads it back): what `strata sim --stereo` writes beside the TUM RGB-D files.
//
// Frames: the session's trajectory is the pose T_W_C of the RGB-D camera; cam0 (left grey camera)
// IS that camera, so the TUM groundtruth.txt is also cam0's trajectory. cam1 sits baseline_m along
// cam0's +x axis (rectified pair). The body frame B is the IMU (imu0 T_BS = identity), mounted at
// T_C_B = imu.T_C_B in cam0's frame; cam0's sensor.yaml T_BS = T_B_C0 = T_C_B^-1, cam1's
// T_B_C1 = T_B_C0 * (baseline_m, 0, 0). Ground truth (state_groundtruth_estimate0) is the body:
// T_W_B = T_W_C T_C_B, the body origin's velocity in W, and the IMU's true biases, at every IMU
// sample. Timestamps: nanoseconds of trajectory time (t = 0 at 0 ns, as the TUM files' seconds).
// Thread safety: the functions may be called from several threads on different folders.
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "strata/io/euroc_types.h"
#include "strata/sim/sensors/grey_camera.h"
#include "strata/sim/sensors/imu.h"
#include "strata/sim/session/sim_session.h"

namespace strata::sim {

/// The IMU mounting used by default: body axes x forward, y left, z up (EuRoC-like) while the
/// camera looks along its z with y down, and a lever arm of a few centimetres.
Eigen::Isometry3d defaultT_C_B();

struct StereoRecordingConfig {
  /// Grey camera resolution (EuRoC: 752x480), focal length (0: 0.61 * width, EuRoC's ratio),
  /// principal point at the image centre, no distortion.
  int width_px = 752;
  int height_px = 480;
  double focal_px = 0.0;
  double baseline_m = 0.11;
  double camera_rate_hz = 20.0;
  double pixel_noise_sigma = 1.0;      // grey levels
  double exposure_gain_sigma = 0.03;   // per frame, relative
  double exposure_offset_sigma = 2.0;  // per frame, grey levels
  /// Stereo (two cameras) or mono (cam0 only).
  bool stereo = true;
  /// IMU at imu.rate_hz (200 Hz default) with Kalibr noise; T_C_B defaults to defaultT_C_B().
  ImuConfig imu = defaultImuConfig();
  /// > 0: record only the first duration_s seconds of the trajectory (short test sessions).
  double duration_s = 0.0;
  /// Rendering threads (0 = all cores); the bytes never depend on it.
  int threads = 0;

  static ImuConfig defaultImuConfig();
  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// The calibration the recording writes (sensor.yaml contents).
euroc::Calibration stereoCalibration(const StereoRecordingConfig& config);

struct StereoRecordingSummary {
  std::size_t frames = 0;
  std::size_t imu_samples = 0;
  double duration_s = 0.0;
};

/// A session's grey camera + IMU in memory, what writeStereoRecording writes: the calibration,
/// the IMU samples and body truth (computed at construction), and the frames rendered on demand.
/// Borrows the session, which must outlive it. Thread safety: const methods may be called from
/// several threads at once.
class StereoRecording {
 public:
  /// Throws InputError for a bad config.
  StereoRecording(const SimSessionDataset& session, const StereoRecordingConfig& config);
  ~StereoRecording();

  const euroc::Calibration& calibration() const { return calibration_; }
  /// Frame timestamps, ns, increasing.
  const std::vector<std::int64_t>& frameTimestamps() const { return frame_ns_; }
  /// Renders frame k: [left] or [left, right] in eyes. Same seed (the session's), same bytes.
  GreyFrame renderFrame(std::size_t k) const;
  /// The IMU samples (IMU frame = body) and the body's true states at each of them.
  const std::vector<euroc::ImuSample>& imu() const { return imu_; }
  const std::vector<euroc::GroundTruthState>& groundTruth() const { return truth_; }
  /// First to last frame time, seconds.
  double duration_s() const;

 private:
  const SimSessionDataset& session_;
  StereoRecordingConfig config_;
  euroc::Calibration calibration_;
  std::unique_ptr<GreyCamera> camera_;
  std::vector<double> frame_times_s_;
  std::vector<std::int64_t> frame_ns_;
  std::vector<euroc::ImuSample> imu_;
  std::vector<euroc::GroundTruthState> truth_;
};

/// Renders and writes <folder>/mav0/{cam0, cam1, imu0, state_groundtruth_estimate0} and the body
/// truth again as a TUM trajectory, <folder>/groundtruth_body.txt (for TUM tools): a
/// StereoRecording on disk. `on_frame` (optional) is called after each written frame.
/// Throws InputError for a bad config, Error when a file cannot be written.
StereoRecordingSummary writeStereoRecording(const SimSessionDataset& session,
                                            const StereoRecordingConfig& config,
                                            const std::string& folder,
                                            const std::function<void()>& on_frame = {});

/// Frames writeStereoRecording will write (for progress bars) and a StereoRecording holds.
std::size_t stereoFrameCount(const SimSessionDataset& session, const StereoRecordingConfig& config);

}  // namespace strata::sim
