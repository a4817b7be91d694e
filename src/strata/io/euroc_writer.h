#pragma once
// Writes an EuRoC/ASL session (the layout io/euroc_dataset.h reads): sensor.yaml files, grey PNG
// frames with their data.csv, imu0/data.csv and the ground truth. Used by `strata sim --stereo`
// and by tests. Every file is written atomically (core/atomic_file.h); Error names the path.
// Thread safety: not thread safe.
#include <cstdint>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/io/euroc_types.h"

namespace strata::euroc {

/// sensor.yaml text with EuRoC's keys (and its "%YAML:1.0" first line).
std::string cameraYaml(const CameraCalibration& camera);
std::string imuYaml(const ImuCalibration& imu);

/// imu0/data.csv (EuRoC header; 17 significant digits).
void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples);
/// state_groundtruth_estimate0/data.csv: 17 columns (zeros where has_velocity_and_biases is
/// false).
void writeGroundTruthCsv(const std::string& path, const std::vector<GroundTruthState>& states);

/// The same poses as a TUM trajectory (`t_s tx ty tz qx qy qz qw`, body-to-world, ns as seconds
/// with 9 decimals), e.g. <session>/groundtruth_body.txt for TUM-format evaluation tools.
void writeGroundTruthTum(const std::string& path, const std::vector<GroundTruthState>& states);

class EurocWriter {
 public:
  /// Creates <session>/mav0/cam0 (+ cam1 when calibration is stereo) and imu0, and writes their
  /// sensor.yaml files.
  EurocWriter(const std::string& session_folder, const Calibration& calibration);

  /// Writes data/<timestamp_ns>.png for each eye (right only for stereo). Throws InputError when
  /// an image is not of its camera's resolution or timestamps do not increase.
  void addFrame(std::int64_t timestamp_ns, const GreyImage& left, const GreyImage& right = {});
  /// Writes the cameras' data.csv, imu0/data.csv and (when not empty) the ground truth.
  void finish(const std::vector<ImuSample>& imu, const std::vector<GroundTruthState>& truth);

  const std::string& mav0() const { return mav0_; }

 private:
  std::string mav0_;
  Calibration calibration_;
  std::vector<std::int64_t> timestamps_ns_;
};

}  // namespace strata::euroc
