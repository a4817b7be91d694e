#include "cli/plan_load.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli/run_outputs.h"
#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/map/map_file.h"

namespace strata::apps {
namespace {

void checkEsdfMaxDistance(float esdf_max_distance_m) {
  if (!std::isfinite(esdf_max_distance_m) || esdf_max_distance_m <= 0.0f) {
    char text[120];
    std::snprintf(text, sizeof(text),
                  "--esdf-max-distance must be a finite number > 0 (metres), not %g",
                  static_cast<double>(esdf_max_distance_m));
    throw InputError(text);
  }
}

}  // namespace

LoadedEsdf loadEsdf(const std::string& map_path, float esdf_max_distance_m,
                    const std::string& device) {
  checkEsdfMaxDistance(esdf_max_distance_m);
  // The file first, on the host: a missing or corrupt map fails before the device is opened.
  const TsdfMap map = loadMap(map_path);
  LoadedEsdf out;
  vk::ContextOptions context_options;
  context_options.device_selector = device;
  out.context = vk::Context::create(context_options);
  MapperConfig config;
  config.esdf = true;
  config.esdf_config.max_distance_m = esdf_max_distance_m;
  out.mapper = Mapper::fromMap(map, *out.context, config);
  const auto start = std::chrono::steady_clock::now();
  out.mapper->updateEsdf();
  out.esdf = &out.mapper->esdf();
  out.esdf_ms = msSince(start);
  return out;
}

void checkRadius(float radius_m, float esdf_max_distance_m) {
  checkEsdfMaxDistance(esdf_max_distance_m);
  char text[200];
  if (!std::isfinite(radius_m) || radius_m < 0.0f) {
    std::snprintf(text, sizeof(text), "--radius must be a finite number >= 0 (metres), not %g",
                  static_cast<double>(radius_m));
    throw InputError(text);
  }
  if (!(radius_m < esdf_max_distance_m)) {
    std::snprintf(text, sizeof(text),
                  "--radius %g m must be below --esdf-max-distance %g m (no larger sphere can "
                  "be free): lower --radius or raise --esdf-max-distance",
                  static_cast<double>(radius_m), static_cast<double>(esdf_max_distance_m));
    throw InputError(text);
  }
}

void checkMapOutputs(const std::string& map_path, const std::string& out_dir,
                     const std::vector<std::string>& files) {
  OutputPaths paths;
  paths.inputFile(map_path, "the map");
  outputFolderFiles(paths, out_dir, "--out", files);
  paths.check();
}

Eigen::Vector3f parsePoint(const std::string& option, const std::string& text) {
  std::stringstream in(text);
  std::string part;
  Eigen::Vector3f p;
  int n = 0;
  while (std::getline(in, part, ',')) {
    std::size_t used = 0;
    float value = NAN;
    try {
      value = std::stof(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (n >= 3 || used == 0 || part.find_first_not_of(" \t", used) != std::string::npos ||
        !std::isfinite(value)) {
      throw InputError(option + " must be three finite numbers x,y,z in metres (got '" + text +
                       "')");
    }
    p[n++] = value;
  }
  if (n != 3) {
    throw InputError(option + " must be three finite numbers x,y,z in metres (got '" + text + "')");
  }
  return p;
}

UnknownPolicy parseUnknownPolicy(const std::string& text) {
  if (text == "occupied") return UnknownPolicy::kOccupied;
  if (text == "free") return UnknownPolicy::kFree;
  throw InputError("--unknown must be 'occupied' or 'free' (got '" + text + "')");
}

}  // namespace strata::apps
