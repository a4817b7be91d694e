#include "strata/mapper/mapper_config.h"

#include <sstream>

#include "strata/core/error.h"

namespace strata {

void MapperConfig::validate() const {
  map.validate();
  if (esdf) esdf_config.validate(map.voxel_size_m);
  if (change_detection) {
    change.validate(map.voxel_size_m);
    objects.validate();
  }
  if (keyframe_scoring) scorer.validate();
  track.validate();
}

std::string MapperConfig::describe() const {
  std::ostringstream out;
  out << map.describe();
  if (esdf) out << ", ESDF to " << esdf_config.max_distance_m << " m";
  if (change_detection) out << ", change detection";
  if (keyframe_scoring) out << ", keyframe scoring";
  return out.str();
}

}  // namespace strata
