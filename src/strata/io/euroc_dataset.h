#pragma once
// EuRoC MAV / ASL session folder reader (grey stereo or mono cameras + IMU + ground truth), for
// visual-inertial odometry. Layout (frames and T_BS: io/euroc_types.h):
//   <session>/mav0/cam0/{sensor.yaml, data.csv, data/<timestamp>.png}   left (or only) camera
//   <session>/mav0/cam1/...                                             right camera (optional)
//   <session>/mav0/imu0/{sensor.yaml, data.csv}
//   <session>/mav0/state_groundtruth_estimate0/data.csv                 ground truth (optional)
//   <session>/groundtruth_body.txt                                      TUM body ground truth,
//                                                                        read when the above is
//                                                                        absent
// NOTE: a root groundtruth.txt is NOT read: in Strata's simulated sessions it is the TUM RGB-D
// camera trajectory (T_W_C of the depth camera), not the body.
//
// What open() checks, and what happens:
//   error (InputError naming the path, and the line or field): a missing folder or file, a
//     data.csv none of whose images exists, a malformed row or yaml key, timestamps that repeat or
//     go back in any data.csv (EuRoC writes them in order: either means a corrupt file),
//     calibration that cannot describe the images (non-positive focal length, principal point
//     outside the image, unknown distortion model, non-rigid T_BS), the first frame's images not of
//     the sensor.yaml resolution, no IMU sample, no stereo pair.
//   counted in stats() and dropped: IMU rows with NaN/inf values; data.csv rows whose image file
//     is absent (excerpts keep the full csv); cam0/cam1 rows with no partner within
//     options.stereo_tolerance_ns.
//   counted in stats() only: IMU gaps (intervals over 1.5 periods at imu rate_hz) and the
//     samples they lack.
// loadImages() checks every later image's size (InputError naming the file and both sizes).
//
// Replay, e.g. in a VIO front end:
//   const euroc::EurocDataset d = euroc::EurocDataset::open(folder);
//   for (const euroc::Event& e : d.events()) {
//     if (e.kind == euroc::Event::Kind::kImu) addImu(d.imu()[e.index]);
//     else addFrame(d.frames()[e.index].timestamp_ns, d.loadImages(e.index));
//   }
// with the cameras' T_B_C and the IMU noise from d.calibration().
//
// Thread safety: an opened dataset is immutable; every const method may be called from several
// threads at once.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/io/euroc_types.h"

namespace strata::euroc {

struct ReaderOptions {
  /// cam0 and cam1 rows pair when their timestamps differ by at most this (EuRoC's agree exactly).
  std::int64_t stereo_tolerance_ns = 1'000'000;
  /// Read the right camera when cam1 is present (false: mono from cam0 alone).
  bool use_right_camera = true;
};

struct StereoImages {
  GreyImage left;
  GreyImage right;  // empty for mono
};

class EurocDataset {
 public:
  /// Opens `folder`: the session folder holding mav0/, or mav0/ itself. Throws InputError (above).
  static EurocDataset open(const std::string& folder, const ReaderOptions& options = {});

  /// The folder as opened, and its mav0 folder.
  const std::string& folder() const { return folder_; }
  const std::string& mav0() const { return mav0_; }

  const Calibration& calibration() const { return calibration_; }
  bool stereo() const { return calibration_.stereo(); }
  /// IMU samples in strictly increasing time (non-finite rows removed).
  const std::vector<ImuSample>& imu() const { return imu_; }
  /// Camera frames (stereo pairs, or cam0 alone for mono) in strictly increasing time.
  const std::vector<StereoFrame>& frames() const { return frames_; }
  /// Ground truth in strictly increasing time; empty when the session has none.
  const std::vector<GroundTruthState>& groundTruth() const { return ground_truth_; }
  /// The file the ground truth came from ("" when none).
  const std::string& groundTruthFile() const { return ground_truth_file_; }
  const ReaderStats& stats() const { return stats_; }

  /// IMU samples and frames merged in time order for replay. At equal timestamps the IMU sample
  /// comes first, so a consumer has every sample up to a frame's time when the frame arrives.
  std::vector<Event> events() const;

  /// Decodes frame `index`'s grey images. Throws InputError for an index out of range, an
  /// unreadable file, a non-8-bit-grey file, or an image whose size is not the sensor.yaml
  /// resolution (naming the file and both sizes).
  StereoImages loadImages(std::size_t index) const;

 private:
  EurocDataset() = default;

  std::string folder_;
  std::string mav0_;
  Calibration calibration_;
  std::vector<ImuSample> imu_;
  std::vector<StereoFrame> frames_;
  std::vector<GroundTruthState> ground_truth_;
  std::string ground_truth_file_;
  ReaderStats stats_;
};

/// The calibration alone (cam0, cam1 when present and `use_right_camera`, imu0 sensor.yaml files)
/// of a session folder or its mav0/, for live consumers that get the images and IMU elsewhere
/// (over LCM). Same checks and InputError messages as open() for those files.
Calibration readCalibration(const std::string& folder, bool use_right_camera = true);

/// Whether `folder` looks like an EuRoC session (has mav0/cam0 or is mav0 with cam0/); no checks.
bool isEurocFolder(const std::string& folder);

/// Body pose at `timestamp_ns` from time-ordered ground truth: translation interpolated linearly,
/// rotation by slerp between the two states around it. nullopt outside the truth's span or when
/// those two states are more than `max_gap_ns` apart (a hole in the truth).
std::optional<Eigen::Isometry3d> interpolateGroundTruth(const std::vector<GroundTruthState>& truth,
                                                        std::int64_t timestamp_ns,
                                                        std::int64_t max_gap_ns = 100'000'000);

/// Reads and checks one grey image against a camera's resolution (loadImages does this per eye).
GreyImage loadGreyImage(const std::string& path, const CameraCalibration& camera);

}  // namespace strata::euroc
