#pragma once
// What `strata plan` and `strata topo` share: a saved map's ESDF on the host (Mapper::load with
// the ESDF on, one full update, the host copy), option parsing of points and policies.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "strata/esdf/esdf_query.h"
#include "strata/mapper/mapper.h"
#include "strata/vk/vk.h"

namespace strata::apps {

struct LoadedEsdf {
  std::unique_ptr<vk::Context> context;
  std::unique_ptr<Mapper> mapper;
  const EsdfMap* esdf = nullptr;  // owned by mapper
  double esdf_ms = 0.0;           // the full ESDF update, wall clock
};

/// InputError naming the file when it is missing or corrupt, or the max distance is bad;
/// DeviceError from the device.
LoadedEsdf loadEsdf(const std::string& map_path, float esdf_max_distance_m,
                    const std::string& device);

/// "x,y,z" (metres) -> point; InputError naming `option` unless three finite numbers.
Eigen::Vector3f parsePoint(const std::string& option, const std::string& text);

/// "occupied" or "free"; InputError otherwise.
UnknownPolicy parseUnknownPolicy(const std::string& text);

}  // namespace strata::apps
