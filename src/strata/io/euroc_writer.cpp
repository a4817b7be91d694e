#include "strata/io/euroc_writer.h"

#include <cstdio>
#include <filesystem>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/io/image_io.h"
#include "strata/io/tum_format.h"

namespace strata::euroc {
namespace {

namespace fs = std::filesystem;

std::string format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), fmt, value);
  return buffer;
}

std::string transformYaml(const Eigen::Isometry3d& T) {
  std::string out = "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  const Eigen::Matrix4d M = T.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      out += format("%.17g", M(r, c));
      if (r < 3 || c < 3) out += (c == 3 ? ",\n         " : ", ");
    }
  }
  return out + "]\n";
}

const char* distortionName(DistortionModel model) {
  switch (model) {
    case DistortionModel::kRadialTangential:
      return "radial-tangential";
    case DistortionModel::kEquidistant:
      return "equidistant";
    case DistortionModel::kNone:
      break;
  }
  return "none";
}

}  // namespace

std::string cameraYaml(const CameraCalibration& c) {
  std::string out = "%YAML:1.0\nsensor_type: camera\ncomment: " + c.name + "\n\n";
  out += "# Sensor extrinsics wrt. the body-frame.\n" + transformYaml(c.T_B_C) + "\n";
  out += "rate_hz: " + format("%.17g", c.rate_hz) + "\n";
  out += "resolution: [" + std::to_string(c.width_px) + ", " + std::to_string(c.height_px) + "]\n";
  out += "camera_model: pinhole\n";
  out += "intrinsics: [" + format("%.17g", c.fu_px) + ", " + format("%.17g", c.fv_px) + ", " +
         format("%.17g", c.cu_px) + ", " + format("%.17g", c.cv_px) + "] #fu, fv, cu, cv\n";
  out += std::string("distortion_model: ") + distortionName(c.distortion) + "\n";
  out += "distortion_coefficients: [";
  for (std::size_t i = 0; i < 4; ++i) {
    out += format("%.17g", c.distortion_coefficients[i]) + (i < 3 ? ", " : "]\n");
  }
  return out;
}

std::string imuYaml(const ImuCalibration& imu) {
  std::string out = "%YAML:1.0\nsensor_type: imu\ncomment: imu0\n\n";
  out += "# Sensor extrinsics wrt. the body-frame.\n" + transformYaml(imu.T_B_I);
  out += "rate_hz: " + format("%.17g", imu.rate_hz) + "\n\n";
  out += "# inertial sensor noise model parameters (static)\n";
  out += "gyroscope_noise_density: " + format("%.17g", imu.gyro_noise_density) +
         "     # [ rad / s / sqrt(Hz) ]\n";
  out += "gyroscope_random_walk: " + format("%.17g", imu.gyro_random_walk) +
         "       # [ rad / s^2 / sqrt(Hz) ]\n";
  out += "accelerometer_noise_density: " + format("%.17g", imu.accel_noise_density) +
         "  # [ m / s^2 / sqrt(Hz) ]\n";
  out += "accelerometer_random_walk: " + format("%.17g", imu.accel_random_walk) +
         "    # [ m / s^3 / sqrt(Hz) ]\n";
  return out;
}

void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples) {
  std::string text =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  char line[512];
  for (const ImuSample& s : samples) {
    const int n =
        std::snprintf(line, sizeof(line), "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                      static_cast<long long>(s.timestamp_ns), s.gyro_rad_s.x(), s.gyro_rad_s.y(),
                      s.gyro_rad_s.z(), s.accel_mps2.x(), s.accel_mps2.y(), s.accel_mps2.z());
    text.append(line, static_cast<std::size_t>(n));
  }
  writeTextAtomically(path, text);
}

void writeGroundTruthCsv(const std::string& path, const std::vector<GroundTruthState>& states) {
  std::string text =
      "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], "
      "b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], "
      "b_a_RS_S_z [m s^-2]\n";
  char line[1024];
  for (const GroundTruthState& s : states) {
    const Eigen::Vector3d p = s.T_W_B.translation();
    const Eigen::Quaterniond q(s.T_W_B.linear());
    const int n = std::snprintf(
        line, sizeof(line),
        "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
        "%.17g,%.17g,%.17g\n",
        static_cast<long long>(s.timestamp_ns), p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(),
        s.velocity_W.x(), s.velocity_W.y(), s.velocity_W.z(), s.gyro_bias.x(), s.gyro_bias.y(),
        s.gyro_bias.z(), s.accel_bias.x(), s.accel_bias.y(), s.accel_bias.z());
    text.append(line, static_cast<std::size_t>(n));
  }
  writeTextAtomically(path, text);
}

void writeGroundTruthTum(const std::string& path, const std::vector<GroundTruthState>& states) {
  std::string text =
      "# body (= IMU) pose in the world, TUM format: timestamp[s] tx ty tz qx qy qz qw\n";
  char stamp[48];
  for (const GroundTruthState& s : states) {
    std::snprintf(stamp, sizeof(stamp), "%lld.%09lld ",
                  static_cast<long long>(s.timestamp_ns / 1'000'000'000),
                  static_cast<long long>(s.timestamp_ns % 1'000'000'000));
    text += stamp + tum::poseToTum(s.T_W_B) + "\n";
  }
  writeTextAtomically(path, text);
}

EurocWriter::EurocWriter(const std::string& session_folder, const Calibration& calibration)
    : mav0_((fs::path(session_folder) / "mav0").string()), calibration_(calibration) {
  if (calibration_.cameras.empty() || calibration_.cameras.size() > 2) {
    throw InputError("EurocWriter: one or two cameras, not " +
                     std::to_string(calibration_.cameras.size()));
  }
  for (const CameraCalibration& camera : calibration_.cameras) {
    const fs::path dir = fs::path(mav0_) / camera.name;
    fs::create_directories(dir / "data");
    writeTextAtomically(dir / "sensor.yaml", cameraYaml(camera));
  }
  fs::create_directories(fs::path(mav0_) / "imu0");
  writeTextAtomically(fs::path(mav0_) / "imu0" / "sensor.yaml", imuYaml(calibration_.imu));
}

void EurocWriter::addFrame(std::int64_t timestamp_ns, const GreyImage& left,
                           const GreyImage& right) {
  if (!timestamps_ns_.empty() && timestamp_ns <= timestamps_ns_.back()) {
    throw InputError("EurocWriter: frame timestamp " + std::to_string(timestamp_ns) +
                     " does not increase");
  }
  const GreyImage* eyes[2] = {&left, &right};
  for (std::size_t i = 0; i < calibration_.cameras.size(); ++i) {
    const CameraCalibration& camera = calibration_.cameras[i];
    if (eyes[i]->width_px != camera.width_px || eyes[i]->height_px != camera.height_px) {
      throw InputError("EurocWriter: " + camera.name + " image is " +
                       std::to_string(eyes[i]->width_px) + "x" +
                       std::to_string(eyes[i]->height_px) + ", calibration says " +
                       std::to_string(camera.width_px) + "x" + std::to_string(camera.height_px));
    }
    writeGreyPng(
        (fs::path(mav0_) / camera.name / "data" / (std::to_string(timestamp_ns) + ".png")).string(),
        *eyes[i]);
  }
  timestamps_ns_.push_back(timestamp_ns);
}

void EurocWriter::finish(const std::vector<ImuSample>& imu,
                         const std::vector<GroundTruthState>& truth) {
  std::string csv = "#timestamp [ns],filename\n";
  for (std::int64_t t : timestamps_ns_)
    csv += std::to_string(t) + "," + std::to_string(t) + ".png\n";
  for (const CameraCalibration& camera : calibration_.cameras) {
    writeTextAtomically(fs::path(mav0_) / camera.name / "data.csv", csv);
  }
  writeImuCsv((fs::path(mav0_) / "imu0" / "data.csv").string(), imu);
  if (!truth.empty()) {
    const fs::path dir = fs::path(mav0_) / "state_groundtruth_estimate0";
    fs::create_directories(dir);
    writeGroundTruthCsv((dir / "data.csv").string(), truth);
  }
}

}  // namespace strata::euroc
