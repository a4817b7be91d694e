#pragma once
// What `strata plan` and `strata topo` share: a saved map's ESDF on the host (Mapper::load with
// the ESDF on, one full update, the host copy), option parsing of points and policies.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

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

/// InputError naming the file when it is missing or corrupt (read and checked on the host before
/// the device is opened), or the max distance is bad; DeviceError from the device.
LoadedEsdf loadEsdf(const std::string& map_path, float esdf_max_distance_m,
                    const std::string& device);

/// --esdf-max-distance a finite number > 0, --radius a finite number >= 0 below it; InputError
/// naming the option and what it accepts otherwise. Reads nothing.
void checkRadius(float radius_m, float esdf_max_distance_m);

/// The map (an input) against the output folder `out_dir` (--out) and the `files` written into
/// it: InputError naming the output and what it collides with (core/output_paths.h) when one
/// cannot be written or would overwrite the map. Reads and creates nothing.
void checkMapOutputs(const std::string& map_path, const std::string& out_dir,
                     const std::vector<std::string>& files);

/// "x,y,z" (metres) -> point; InputError naming `option` unless three finite numbers.
Eigen::Vector3f parsePoint(const std::string& option, const std::string& text);

/// "occupied" or "free"; InputError otherwise.
UnknownPolicy parseUnknownPolicy(const std::string& text);

}  // namespace strata::apps
