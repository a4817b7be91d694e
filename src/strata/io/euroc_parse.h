#pragma once
// Parsers of the EuRoC/ASL text files, from their text (the reader in io/euroc_dataset.h reads the
// files with size limits first; the fuzz targets call these directly). Each throws InputError
// "<name>: ..." or "<name>:<line>: ..." naming the field or row at fault.
#include <cstdint>
#include <string>
#include <vector>

#include "strata/io/euroc_types.h"

namespace strata::euroc {

// Checked before a file is read: an hour of IMU at 200 Hz is ~100 MB of CSV; a sensor.yaml is
// well under a kilobyte.
inline constexpr std::uint64_t kMaxCsvBytes = std::uint64_t{256} << 20;
inline constexpr std::uint64_t kMaxYamlBytes = std::uint64_t{1} << 20;

/// A camera sensor.yaml. Accepts EuRoC's OpenCV-style first line "%YAML:1.0" (which yaml-cpp
/// rejects as a directive). Checks: sensor_type camera (when given), camera_model pinhole (when
/// given), rate_hz > 0, resolution [w, h] within core/image_limits.h, intrinsics [fu fv cu cv]
/// with fu, fv > 0 and the principal point inside the image, distortion_model radial-tangential /
/// radtan / plumb_bob, equidistant or none with 4 coefficients (none: absent or all zero), T_BS a
/// 4x4 rigid transform (orthonormal to 1e-4, det +1, last row 0 0 0 1).
CameraCalibration parseCameraYaml(const std::string& text, const std::string& name);

/// imu0's sensor.yaml: rate_hz > 0, the four noise terms finite and >= 0, T_BS rigid.
ImuCalibration parseImuYaml(const std::string& text, const std::string& name);

/// One row of a camera's data.csv: `timestamp_ns,filename`.
struct ImageRow {
  std::int64_t timestamp_ns = 0;
  std::string filename;
};

/// A camera's data.csv. '#' lines and blank lines skipped, CRLF accepted. Timestamps must be
/// strictly increasing: a duplicate or a step back is an error naming the line (EuRoC files are
/// written in order, so either means a corrupt or hand-edited file).
std::vector<ImageRow> parseImageCsv(const std::string& text, const std::string& name);

struct ImuCsv {
  std::vector<ImuSample> samples;
  std::size_t rows = 0;               // data rows
  std::size_t nonfinite_skipped = 0;  // rows with a NaN or inf value, left out of samples
};

/// imu0/data.csv: `timestamp_ns,wx,wy,wz,ax,ay,az`. Same ordering rule as parseImageCsv (a
/// skipped non-finite row still takes part in it).
ImuCsv parseImuCsv(const std::string& text, const std::string& name);

/// mav0/state_groundtruth_estimate0/data.csv: `timestamp_ns, p xyz, q wxyz, v xyz, bw xyz,
/// ba xyz` (17 columns; 8 columns = pose only). Quaternion normalised (zero: error). Same
/// ordering rule; non-finite values are errors.
std::vector<GroundTruthState> parseGroundTruthCsv(const std::string& text, const std::string& name);

/// TUM trajectory `timestamp_s tx ty tz qx qy qz qw` (body-to-world), e.g. groundtruth_body.txt.
/// Timestamps rounded to nanoseconds; strictly increasing after rounding.
std::vector<GroundTruthState> parseGroundTruthTum(const std::string& text, const std::string& name);

}  // namespace strata::euroc
