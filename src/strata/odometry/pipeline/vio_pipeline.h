#pragma once
// Visual-inertial odometry from raw sensor streams: grey stereo (or mono) images and IMU samples
// in, camera poses out. Joins the front end (odometry/frontend/feature_tracker.h: KLT tracks,
// stereo matches, outlier rejection) and the sliding-window back end (odometry/vio_estimator.h)
// and handles what a live stream does wrong:
//   - frames and IMU samples arrive on different channels: a frame waits (queued, at most
//     max_pending_frames) until an IMU sample at or after its time has arrived;
//   - IMU samples with NaN/inf values, or not after the previous one, are counted and skipped;
//   - frames not after the previous one, and frames whose IMU never arrives (queue overflow or
//     flush()), are counted and skipped;
//   - images of the wrong size or type: InputError from push() naming the eye and both sizes
//     (the caller counts and skips, or ends the run); nothing of the state is changed.
// The gyro, integrated between frames with the current bias estimate, predicts the camera's
// rotation for KLT.
//
// Frames: B = body (IMU), C = left camera (cam0). T_W_C = T_W_B * T_B_C0. The world frame W has z
// up (gravity along -z). Its origin and yaw are where the body was when the estimator first
// initialised, unless an anchor is given (anchor_W_B: W is then the anchor's frame, with the
// first tracked pose's yaw and position taken from it; roll and pitch stay the estimator's own).
// After a failure the estimator re-initialises in a new frame of its own; the pipeline keeps W
// continuous by dead-reckoning the body on the IMU from the last tracked state to the first
// re-initialised frame and mapping the new frame onto W (yaw and position; a stated
// approximation: the dead-reckoned gap adds its drift, a few cm per second without vision). A gap
// over 3 s, or one whose dead reckoning implies an impossible speed, holds the last position.
//
// Timestamps are nanoseconds on one clock for images and IMU (EuRoC's). Internally times are
// seconds from the first timestamp seen.
//
// Not thread safe: one thread pushes everything. OpenCV's thread count is the caller's
// (cv::setNumThreads).
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/io/euroc_types.h"
#include "strata/odometry/camera_rig.h"
#include "strata/odometry/frontend/camera.h"
#include "strata/odometry/frontend/feature_tracker.h"
#include "strata/odometry/vio_estimator.h"

namespace strata::odometry {

struct VioPipelineConfig {
  FrontendConfig frontend;
  /// backend.imu is replaced by the calibration's noise densities when use_calibration_noise.
  VioConfig backend;
  bool use_calibration_noise = true;
  /// Use the left camera only, even when the calibration has a right one.
  bool mono = false;
  /// Frames waiting for their IMU; beyond it the oldest is dropped (counted).
  int max_pending_frames = 20;
  /// Optional truth of the body pose at a time (ns): called at the first initialisation to anchor
  /// W (see above). nullopt from it leaves W the estimator's own.
  std::function<std::optional<Eigen::Isometry3d>(std::int64_t)> anchor_W_B;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// One processed frame.
struct PipelineFrame {
  std::int64_t timestamp_ns = 0;
  VioStatus status = VioStatus::kInitializing;
  std::string reason;  // of kFailed, or what initialisation waits for
  /// kTracking only, in the continuous world frame W (see above).
  Eigen::Isometry3d T_W_B = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_W_B = Eigen::Vector3d::Zero();
  ImuBias bias;
  /// 0 before the first failure, then +1 at each re-initialisation.
  int segment = 0;
  int features = 0;  // front-end observations handed to the back end
  int stereo_matched = 0;
  bool frontend_lost = false;
  int landmarks = 0;
  double frontend_ms = 0.0;  // wall time of the front end
  double backend_ms = 0.0;   // wall time of the back end
};

/// IMU readings beyond these no IMU a robot carries measures (the widest MEMS ranges are about
/// +-4000 deg/s, 70 rad/s, and +-200 g, 1960 m/s^2): such a sample is corrupt and is skipped.
inline constexpr double kMaxImuAngularRate_rad_s = 70.0;
inline constexpr double kMaxImuAcceleration_mps2 = 1960.0;

/// The warning a program prints when `skipped` IMU samples were beyond those limits ("" for 0):
/// "N IMU samples beyond any IMU's range (...) were skipped: are the IMU's units or scale wrong?".
std::string imuOutOfRangeWarning(std::size_t skipped);

struct PipelineStats {
  std::size_t imu_samples = 0;            // accepted
  std::size_t imu_nonfinite_skipped = 0;  // NaN/inf values
  std::size_t imu_out_of_range_skipped = 0;  // beyond kMaxImuAngularRate / kMaxImuAcceleration
  std::size_t imu_out_of_order_skipped = 0;
  std::size_t frames_in = 0;  // pushed
  std::size_t frames_processed = 0;
  std::size_t frames_out_of_order_skipped = 0;
  std::size_t frames_without_imu_skipped = 0;  // pending overflow or flush()
  std::size_t frames_tracking = 0;
  std::size_t frames_initializing = 0;
  std::size_t failures = 0;
  /// How each re-initialisation was joined to W: by dead reckoning over the gap, or (a gap over
  /// 3 s, or one implying a speed over the back end's max_speed_mps) holding the last position.
  std::size_t reanchored_dead_reckoned = 0;
  std::size_t reanchored_position_held = 0;
  /// Time of the first tracked frame (ns; -1 before it) and of each failure with its reason.
  std::int64_t first_tracking_ns = -1;
  std::vector<std::pair<std::int64_t, std::string>> failure_log;
  double frontend_ms_total = 0.0;
  double backend_ms_total = 0.0;
};

/// euroc::CameraCalibration -> the front end's camera (distortion model and T_B_C).
Camera frontendCamera(const euroc::CameraCalibration& calibration);
/// The back end's rig: pinhole intrinsics of the undistorted cameras, T_B_C of each; the right
/// camera unless `mono` or the calibration has none.
CameraRig backendRig(const euroc::Calibration& calibration, bool mono);

class VioPipeline {
 public:
  /// Throws InputError for an unusable calibration (e.g. a camera that fails validation, a
  /// stereo pair with no baseline) or config.
  VioPipeline(const euroc::Calibration& calibration, VioPipelineConfig config);
  ~VioPipeline();
  VioPipeline(const VioPipeline&) = delete;
  VioPipeline& operator=(const VioPipeline&) = delete;

  /// One IMU sample (IMU frame = body: T_B_I is applied when it is not the identity). Returns
  /// the pending frames it completes, processed, in time order.
  std::vector<PipelineFrame> pushImu(const euroc::ImuSample& sample);
  /// One camera frame: `left` (and `right` for stereo; ignored for mono) grey 8-bit images of the
  /// calibrated size. Returns the frames processed now (this one once its IMU is there). Throws
  /// InputError for a bad image, with nothing changed.
  std::vector<PipelineFrame> pushFrame(std::int64_t timestamp_ns, const cv::Mat& left,
                                       const cv::Mat& right = cv::Mat());
  /// The same from core GreyImages (an empty right image for mono).
  std::vector<PipelineFrame> pushFrame(std::int64_t timestamp_ns, const GreyImage& left,
                                       const GreyImage& right);
  /// End of stream: frames still waiting for IMU are dropped (counted).
  void flush();

  const PipelineStats& stats() const { return stats_; }
  const CameraRig& rig() const { return rig_; }
  bool stereo() const { return rig_.right.has_value(); }
  VioStatus status() const;

 private:
  struct Pending {
    std::int64_t timestamp_ns;
    cv::Mat left, right;
  };
  std::vector<PipelineFrame> drain();
  std::size_t firstImuCovering(std::int64_t t_ns) const;
  PipelineFrame process(const Pending& frame);
  std::optional<Eigen::Matrix3d> predictCameraRotation(std::int64_t from_ns, std::int64_t to_ns);
  Eigen::Isometry3d deadReckon(std::int64_t to_ns) const;
  Eigen::Isometry3d bridgeGap(std::int64_t to_ns);
  void checkImage(const cv::Mat& image, const Camera& camera, const char* eye) const;
  double seconds(std::int64_t timestamp_ns) const;

  VioPipelineConfig config_;
  Camera left_camera_, right_camera_;
  CameraRig rig_;
  Eigen::Isometry3d T_B_I_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<FeatureTracker> tracker_;
  std::unique_ptr<VioEstimator> estimator_;
  std::optional<std::int64_t> epoch_ns_;
  std::deque<euroc::ImuSample> imu_;  // the last seconds, body frame, for predictions
  std::deque<Pending> pending_;
  std::optional<std::int64_t> last_frame_ns_;
  ImuBias bias_;  // latest estimate, for the gyro prediction and dead reckoning
  // Continuity of W over re-initialisations: T_W_E maps the estimator's current frame E into W.
  Eigen::Isometry3d T_W_E_ = Eigen::Isometry3d::Identity();
  bool anchored_ = false;  // T_W_E_ set for the current estimator frame
  int segment_ = 0;
  struct LastState {
    std::int64_t timestamp_ns = 0;
    Eigen::Isometry3d T_W_B = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_W_B = Eigen::Vector3d::Zero();
  };
  std::optional<LastState> last_tracked_;
  PipelineStats stats_;
};

}  // namespace strata::odometry
