#pragma once
// The volumetric check that accepts or refuses a registered match (Furrer et al. 2018: without it
// false matches accumulate into "the ball of doom"). Two tests:
//  1. SDF agreement: at every surface voxel of the observation (|d| < agreement_band, observed),
//     mapped into M by T_M_O, the model's interpolated distance, where observed, is within
//     sdf_tolerance_m of the observation's. agreement = agreeing / compared; overlap = compared /
//     the observation's surface voxels. Both must reach their minimum. The same the other way
//     round (the model's surface voxels against the observation's distances, where observed):
//     model_agreement must reach min_agreement too; its overlap is not asked for, since one
//     session often sees only part of a model. NOTE: both ways, because the models keep only
//     their truncation band: an observation of a larger shape that swallows the model has most of
//     its surface outside the model's band (not compared), while the model's surface lies inside
//     the observation's band and disagrees there.
//  2. Free space: every surface sample of the model, placed in the world at T_W_M, is looked up in
//     the session map; where the session observed it as free (interpolated distance >
//     free_margin_m with weight >= min_weight), the model puts surface into space the session saw
//     empty. violation = such samples / samples the session observed at all; must stay below
//     max_free_space_violation.
// Identical shapes (two equal chairs) pass; a chair registered onto a box does not.
// NOTE: differences farther than the truncation band from the other shape's surface are not
// compared, so an incomplete model and a smaller object look alike: a model of a 40 cm tall box
// passes against an observation of the same box 50 cm tall, and against one 30 % larger in
// footprint placed corner on corner. min_overlap and the registration decide those.
// Thread safety: free function, no shared state.
#include <Eigen/Geometry>
#include <string>

#include "strata/map/tsdf_map.h"
#include "strata/objects/object_model.h"
#include "strata/objects/object_observation.h"

namespace strata::objects {

struct ConsistencyConfig {
  float agreement_band_voxels = 2.0f;  // observation voxels with |d| below this are compared
  float sdf_tolerance_voxels = 1.0f;   // |d_M - d_O| below this agrees (the coarser grid's voxels)
  float min_agreement = 0.75f;
  float min_overlap = 0.3f;
  float free_margin_voxels = 2.0f;  // session distance above this is free space
  float max_free_space_violation = 0.05f;
  float min_weight = 1e-3f;
  void validate() const;  // InputError naming the bad field
};

struct ConsistencyResult {
  bool accepted = false;
  std::string reason;  // "" when accepted, else which test failed with its figures
  std::size_t observation_surface_voxels = 0;
  std::size_t compared_voxels = 0;
  double agreement = 0.0;
  double overlap = 0.0;
  std::size_t model_compared_voxels = 0;   // model surface voxels the observation observed
  double model_agreement = 0.0;            // agreeing / model_compared_voxels
  std::size_t model_samples_observed = 0;  // model samples the session observed (free or not)
  std::size_t model_samples_in_free_space = 0;
  double free_space_violation = 0.0;
};

/// `session_map` is the observation's session layer (world frame); T_M_O maps the observation's
/// frame into the model's; T_W_M = observation.T_W_O * T_M_O^-1 places the model in that session.
ConsistencyResult checkConsistency(const ObjectModel& model, const ObjectObservation& observation,
                                   const Eigen::Isometry3d& T_M_O, const TsdfMap& session_map,
                                   const ConsistencyConfig& config = {});

}  // namespace strata::objects
