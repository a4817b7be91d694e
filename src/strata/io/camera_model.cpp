#include "strata/io/camera_model.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "strata/core/error.h"
#include "strata/core/file_limits.h"

namespace strata {
namespace {

template <typename T>
T readKey(const YAML::Node& root, const char* key, const std::string& path) {
  try {
    return root[key].as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(path + ": key '" + key + "' has value '" + YAML::Dump(root[key]) +
                     "', which is not a number of the expected type");
  }
}

template <typename T>
void applyKey(const YAML::Node& root, const char* key, const std::string& path, T* value) {
  if (root[key]) *value = readKey<T>(root, key, path);
}

std::vector<std::uint16_t> readInvalidList(const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence())
    throw InputError(path + ": 'depth_invalid' must be a list like [0, 65535]");
  std::vector<std::uint16_t> values;
  for (const YAML::Node& item : node) {
    long long v = -1;
    try {
      v = item.as<long long>();
    } catch (const YAML::Exception&) {
    }
    if (v < 0 || v > std::numeric_limits<std::uint16_t>::max()) {
      throw InputError(path + ": 'depth_invalid' entry '" + YAML::Dump(item) +
                       "' is not a 16-bit PNG value (0..65535)");
    }
    values.push_back(static_cast<std::uint16_t>(v));
  }
  return values;
}

// Checked before a camera file is read: a camera.yaml or a 3x3 K takes well under a kilobyte.
constexpr FileSizeLimit kMaxCameraFileBytes{"kMaxCameraFileBytes", std::uint64_t{1} << 20};

YAML::Node parseYaml(const std::string& text, const std::string& path) {
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw InputError(path + ": camera file is not a YAML map of keys");
    return root;
  } catch (const YAML::Exception& e) {
    throw InputError(path + ": cannot parse camera YAML: " + e.what());
  }
}

void addInvalid(std::uint16_t value, std::vector<std::uint16_t>* values) {
  if (std::find(values->begin(), values->end(), value) == values->end()) values->push_back(value);
}

}  // namespace

void CameraModel::validate() const {
  try {
    intrinsics.validate();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  if (!std::isfinite(depth_scale) || depth_scale <= 0.0) {
    std::ostringstream msg;
    msg << source << ": depth_scale " << depth_scale << " must be finite and positive (PNG units "
        << "per metre)";
    throw InputError(msg.str());
  }
}

void applyCameraYaml(const std::string& path, CameraModel* model) {
  applyCameraYamlText(readTextBounded(path, kMaxCameraFileBytes, "camera file"), path, model);
}

void applyCameraYamlText(const std::string& text, const std::string& path, CameraModel* model) {
  const YAML::Node root = parseYaml(text, path);
  CameraIntrinsics& k = model->intrinsics;
  applyKey(root, "width", path, &k.width_px);
  applyKey(root, "height", path, &k.height_px);
  applyKey(root, "fx", path, &k.fx_px);
  applyKey(root, "fy", path, &k.fy_px);
  applyKey(root, "cx", path, &k.cx_px);
  applyKey(root, "cy", path, &k.cy_px);
  applyKey(root, "depth_scale", path, &model->depth_scale);
  if (root["depth_invalid"]) {
    for (std::uint16_t v : readInvalidList(root["depth_invalid"], path)) {
      addInvalid(v, &model->depth_invalid);
    }
  }
  model->source = path;
}

void applyIntrinsicsMatrixFile(const std::string& path, CameraModel* model) {
  checkFileSize(path, kMaxCameraFileBytes, "intrinsics file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open intrinsics file");
  applyIntrinsicsMatrix(in, path, model);
}

void applyIntrinsicsMatrix(std::istream& in, const std::string& path, CameraModel* model) {
  double k[9];
  for (double& value : k) {
    if (!(in >> value) || !std::isfinite(value)) {
      throw InputError(path + ": expected a 3x3 matrix K of 9 finite numbers");
    }
  }
  model->intrinsics.fx_px = static_cast<float>(k[0]);
  model->intrinsics.cx_px = static_cast<float>(k[2]);
  model->intrinsics.fy_px = static_cast<float>(k[4]);
  model->intrinsics.cy_px = static_cast<float>(k[5]);
  model->source = path;
}

CameraModel resolveCameraModel(const std::string& folder, const DatasetOptions& options,
                               CameraModel defaults) {
  CameraModel model = std::move(defaults);
  addInvalid(0, &model.depth_invalid);
  const std::filesystem::path folder_yaml = std::filesystem::path(folder) / "camera.yaml";
  // Validated after every step so an error names the source that made the model invalid.
  model.validate();
  if (std::filesystem::is_regular_file(folder_yaml)) {
    applyCameraYaml(folder_yaml.string(), &model);
    model.validate();
  }
  if (!options.camera_file.empty()) {
    applyCameraYaml(options.camera_file, &model);
    model.validate();
  }
  if (options.intrinsics) {
    model.intrinsics = *options.intrinsics;
    model.source = "DatasetOptions::intrinsics";
    model.validate();
  }
  if (options.depth_scale) {
    model.depth_scale = *options.depth_scale;
    model.source = "DatasetOptions::depth_scale";
    model.validate();
  }
  return model;
}

}  // namespace strata
