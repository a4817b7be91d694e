#include "cli/plan_load.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "strata/core/clock.h"
#include "strata/core/error.h"

namespace strata::apps {

LoadedEsdf loadEsdf(const std::string& map_path, float esdf_max_distance_m,
                    const std::string& device) {
  if (!std::isfinite(esdf_max_distance_m) || esdf_max_distance_m <= 0.0f) {
    throw InputError("--esdf-max-distance must be positive and finite");
  }
  LoadedEsdf out;
  vk::ContextOptions context_options;
  context_options.device_selector = device;
  out.context = vk::Context::create(context_options);
  MapperConfig config;
  config.esdf = true;
  config.esdf_config.max_distance_m = esdf_max_distance_m;
  out.mapper = Mapper::load(map_path, *out.context, config);
  const auto start = std::chrono::steady_clock::now();
  out.mapper->updateEsdf();
  out.esdf = &out.mapper->esdf();
  out.esdf_ms =
      msSince(start);
  return out;
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
