#include "strata/objects/consistency_check.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "strata/core/error.h"
#include "strata/core/validate.h"
#include "strata/objects/internal/block_sets.h"

namespace strata::objects {
namespace {

struct Agreement {
  std::size_t surface = 0, compared = 0, agreeing = 0;
};

/// Test 1, one direction: the near-surface voxels of `from` against the distances of `to` at the
/// same place (T_to_from maps from's frame into to's).
Agreement sdfAgreement(const TsdfMap& from, const TsdfMap& to, const Eigen::Isometry3d& T_to_from,
                       const ConsistencyConfig& config) {
  const float from_voxel_m = from.config().voxel_size_m;
  const float band_m = config.agreement_band_voxels * from_voxel_m;
  // The coarser grid bounds how well the two can agree.
  const float tolerance_m =
      config.sdf_tolerance_voxels * std::max(from_voxel_m, to.config().voxel_size_m);
  Agreement out;
  for (const BlockIndex& b : from.sortedBlockIndices()) {
    const TsdfBlock& block = *from.findBlock(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const TsdfVoxel& voxel = block[static_cast<std::size_t>(i)];
      if (voxel.weight < config.min_weight || voxel.weight <= 0.0f) continue;
      if (std::abs(voxel.tsdf_m) >= band_m) continue;
      ++out.surface;
      const GlobalVoxelIndex v = voxelOfBlock(b, i);
      const Eigen::Vector3d p_to = T_to_from * voxelCenter(v, from_voxel_m).cast<double>();
      const auto sample = sampleTsdf(to, p_to.cast<float>(), config.min_weight);
      if (!sample) continue;
      ++out.compared;
      if (std::abs(sample->distance_m - voxel.tsdf_m) < tolerance_m) ++out.agreeing;
    }
  }
  return out;
}

double share(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

/// Test 2: the model's surface samples placed in the session, against what the session saw free.
void freeSpace(const ObjectModel& model, const Eigen::Isometry3d& T_W_M, const TsdfMap& session_map,
               const ConsistencyConfig& config, ConsistencyResult& result) {
  const float free_m = config.free_margin_voxels * session_map.config().voxel_size_m;
  for (const Eigen::Vector3f& p_M : model.surface_M.points) {
    const Eigen::Vector3d p_W = T_W_M * p_M.cast<double>();
    const auto sample = sampleTsdf(session_map, p_W.cast<float>(), config.min_weight);
    if (!sample) continue;
    ++result.model_samples_observed;
    if (sample->distance_m > free_m) ++result.model_samples_in_free_space;
  }
  result.free_space_violation =
      share(result.model_samples_in_free_space, result.model_samples_observed);
}

void requireUnit(float v, const char* field) {
  if (!std::isfinite(v) || v < 0.0f || v > 1.0f) {
    throw InputError(std::string("invalid consistency config: ") + field + " must be in [0, 1]");
  }
}

}  // namespace

void ConsistencyConfig::validate() const {
  requirePositive(agreement_band_voxels, "ConsistencyConfig", "agreement_band_voxels");
  requirePositive(sdf_tolerance_voxels, "ConsistencyConfig", "sdf_tolerance_voxels");
  requireUnit(min_agreement, "min_agreement");
  requireUnit(min_overlap, "min_overlap");
  requirePositive(free_margin_voxels, "ConsistencyConfig", "free_margin_voxels");
  requireUnit(max_free_space_violation, "max_free_space_violation");
  if (!std::isfinite(min_weight) || min_weight < 0.0f) {
    throw InputError("invalid consistency config: min_weight must be >= 0");
  }
}

ConsistencyResult checkConsistency(const ObjectModel& model, const ObjectObservation& observation,
                                   const Eigen::Isometry3d& T_M_O, const TsdfMap& session_map,
                                   const ConsistencyConfig& config) {
  config.validate();
  if (!T_M_O.matrix().allFinite()) throw InputError("checkConsistency: T_M_O is not finite");
  ConsistencyResult result;
  const Agreement a = sdfAgreement(observation.tsdf, model.tsdf, T_M_O, config);
  result.observation_surface_voxels = a.surface;
  result.compared_voxels = a.compared;
  result.agreement = share(a.agreeing, a.compared);
  result.overlap = share(a.compared, a.surface);
  const Agreement m = sdfAgreement(model.tsdf, observation.tsdf, T_M_O.inverse(), config);
  result.model_compared_voxels = m.compared;
  result.model_agreement = share(m.agreeing, m.compared);
  freeSpace(model, observation.T_W_O * T_M_O.inverse(), session_map, config, result);

  std::ostringstream reason;
  if (result.overlap < config.min_overlap) {
    reason << "overlap " << result.overlap << " < min_overlap " << config.min_overlap << " ("
           << a.compared << " of " << a.surface << " observation surface voxels compared)";
  } else if (result.agreement < config.min_agreement) {
    reason << "SDF agreement " << result.agreement << " < min_agreement " << config.min_agreement
           << " (" << a.agreeing << " of " << a.compared << " voxels agree)";
  } else if (result.model_agreement < config.min_agreement) {
    reason << "model SDF agreement " << result.model_agreement << " < min_agreement "
           << config.min_agreement << " (" << m.agreeing << " of " << m.compared
           << " model surface voxels agree)";
  } else if (result.free_space_violation > config.max_free_space_violation) {
    reason << "free space violation " << result.free_space_violation
           << " > max_free_space_violation " << config.max_free_space_violation << " ("
           << result.model_samples_in_free_space << " of " << result.model_samples_observed
           << " model samples in space the session saw free)";
  }
  result.reason = reason.str();
  result.accepted = result.reason.empty();
  return result;
}

}  // namespace strata::objects
