// sensor.yaml parsing for the EuRoC reader (io/euroc_parse.h).
#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <cmath>
#include <sstream>

#include "strata/core/error.h"
#include "strata/core/image_limits.h"
#include "strata/io/euroc_parse.h"

namespace strata::euroc {
namespace {

/// yaml-cpp takes "%YAML:1.0" (OpenCV's FileStorage header) for a malformed directive: blank the
/// line, keeping line numbers for yaml-cpp's own messages.
std::string withoutOpenCvHeader(const std::string& text) {
  if (text.rfind("%YAML:", 0) != 0) return text;
  const std::size_t end = text.find('\n');
  return end == std::string::npos ? std::string() : text.substr(end);
}

YAML::Node parseRoot(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(withoutOpenCvHeader(text));
  } catch (const YAML::Exception& e) {
    throw InputError(name + ": cannot parse YAML: " + e.what());
  }
  if (!root.IsMap()) throw InputError(name + ": sensor.yaml is not a YAML map of keys");
  return root;
}

double number(const YAML::Node& node, const std::string& name, const std::string& key) {
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(name + ": '" + key + "' value '" + YAML::Dump(node) + "' is not a number");
  }
  if (!std::isfinite(value)) throw InputError(name + ": '" + key + "' is not finite");
  return value;
}

double requiredNumber(const YAML::Node& root, const std::string& name, const char* key) {
  if (!root[key]) throw InputError(name + ": missing key '" + key + "'");
  return number(root[key], name, key);
}

std::vector<double> numberList(const YAML::Node& node, const std::string& name,
                               const std::string& key, std::size_t count) {
  if (!node || !node.IsSequence() || node.size() != count) {
    throw InputError(name + ": '" + key + "' must be a list of " + std::to_string(count) +
                     " numbers");
  }
  std::vector<double> values;
  for (const YAML::Node& item : node) values.push_back(number(item, name, key));
  return values;
}

std::string text(const YAML::Node& root, const char* key) {
  if (!root[key] || !root[key].IsScalar()) return "";
  return root[key].as<std::string>();
}

/// T_BS: {cols: 4, rows: 4, data: [16 numbers, row-major]}, a rigid transform.
Eigen::Isometry3d readTransform(const YAML::Node& root, const std::string& name) {
  const YAML::Node node = root["T_BS"];
  if (!node || !node.IsMap()) throw InputError(name + ": missing 'T_BS' (rows, cols, data)");
  if ((node["rows"] && number(node["rows"], name, "T_BS.rows") != 4.0) ||
      (node["cols"] && number(node["cols"], name, "T_BS.cols") != 4.0)) {
    throw InputError(name + ": 'T_BS' must be 4x4");
  }
  const std::vector<double> d = numberList(node["data"], name, "T_BS.data", 16);
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = d[static_cast<std::size_t>(4 * r + c)];
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double orthonormal_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  const double last_row_error = (M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm();
  if (orthonormal_error > 1e-4 || R.determinant() <= 0.0 || last_row_error > 1e-9) {
    std::ostringstream msg;
    msg << name << ": 'T_BS' is not a rigid transform (|R^T R - I| = " << orthonormal_error
        << ", det R = " << R.determinant() << ", last row error " << last_row_error << ")";
    throw InputError(msg.str());
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();  // exact rotation
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

void checkSensorType(const YAML::Node& root, const std::string& name, const char* expected) {
  const std::string type = text(root, "sensor_type");
  if (!type.empty() && type != expected) {
    throw InputError(name + ": sensor_type is '" + type + "', expected '" + expected + "'");
  }
}

DistortionModel readDistortion(const YAML::Node& root, const std::string& name,
                               std::array<double, 4>* coefficients) {
  const std::string model = text(root, "distortion_model");
  coefficients->fill(0.0);
  if (root["distortion_coefficients"]) {
    const std::vector<double> d =
        numberList(root["distortion_coefficients"], name, "distortion_coefficients", 4);
    std::copy(d.begin(), d.end(), coefficients->begin());
  }
  const bool all_zero = *coefficients == std::array<double, 4>{};
  if (model == "radial-tangential" || model == "radtan" || model == "plumb_bob")
    return DistortionModel::kRadialTangential;
  if (model == "equidistant") return DistortionModel::kEquidistant;
  if ((model.empty() || model == "none") && all_zero) return DistortionModel::kNone;
  throw InputError(name + ": distortion_model '" + model +
                   "' is not supported (radial-tangential, equidistant, or none with zero "
                   "coefficients)");
}

}  // namespace

CameraCalibration parseCameraYaml(const std::string& yaml, const std::string& name) {
  const YAML::Node root = parseRoot(yaml, name);
  checkSensorType(root, name, "camera");
  const std::string model = text(root, "camera_model");
  if (!model.empty() && model != "pinhole") {
    throw InputError(name + ": camera_model '" + model + "' is not supported (pinhole)");
  }
  CameraCalibration camera;
  camera.rate_hz = requiredNumber(root, name, "rate_hz");
  if (camera.rate_hz <= 0.0) throw InputError(name + ": rate_hz must be positive");
  const std::vector<double> resolution = numberList(root["resolution"], name, "resolution", 2);
  if (resolution[0] != std::floor(resolution[0]) || resolution[1] != std::floor(resolution[1]) ||
      resolution[0] < 1.0 || resolution[1] < 1.0 || resolution[0] > kMaxImageSidePx ||
      resolution[1] > kMaxImageSidePx) {
    throw InputError(name + ": resolution must be two positive whole numbers [width, height] of " +
                     "at most " + std::to_string(kMaxImageSidePx));
  }
  camera.width_px = static_cast<int>(resolution[0]);
  camera.height_px = static_cast<int>(resolution[1]);
  checkImageSize(camera.width_px, camera.height_px, name + ": resolution");
  const std::vector<double> k = numberList(root["intrinsics"], name, "intrinsics", 4);
  camera.fu_px = k[0];
  camera.fv_px = k[1];
  camera.cu_px = k[2];
  camera.cv_px = k[3];
  if (camera.fu_px <= 0.0 || camera.fv_px <= 0.0) {
    throw InputError(name + ": intrinsics focal lengths fu, fv must be positive");
  }
  // Pixel centres at integer coordinates: the image spans [-0.5, width - 0.5].
  if (camera.cu_px < -0.5 || camera.cu_px > camera.width_px - 0.5 || camera.cv_px < -0.5 ||
      camera.cv_px > camera.height_px - 0.5) {
    std::ostringstream msg;
    msg << name << ": principal point (" << camera.cu_px << ", " << camera.cv_px
        << ") is outside the " << camera.width_px << "x" << camera.height_px << " image";
    throw InputError(msg.str());
  }
  camera.distortion = readDistortion(root, name, &camera.distortion_coefficients);
  camera.T_B_C = readTransform(root, name);
  return camera;
}

ImuCalibration parseImuYaml(const std::string& yaml, const std::string& name) {
  const YAML::Node root = parseRoot(yaml, name);
  checkSensorType(root, name, "imu");
  ImuCalibration imu;
  imu.rate_hz = requiredNumber(root, name, "rate_hz");
  if (imu.rate_hz <= 0.0) throw InputError(name + ": rate_hz must be positive");
  const auto nonNegative = [&](const char* key) {
    const double value = requiredNumber(root, name, key);
    if (value < 0.0) throw InputError(name + ": '" + key + "' must be >= 0");
    return value;
  };
  imu.gyro_noise_density = nonNegative("gyroscope_noise_density");
  imu.gyro_random_walk = nonNegative("gyroscope_random_walk");
  imu.accel_noise_density = nonNegative("accelerometer_noise_density");
  imu.accel_random_walk = nonNegative("accelerometer_random_walk");
  imu.T_B_I = readTransform(root, name);
  return imu;
}

}  // namespace strata::euroc
