#pragma once
// An object model of the database: one shape as a TSDF in its own model frame M, the observations
// merged into it, and its instances (where it stood in which session). docs/objects.md.
//
// Merging (mergeObservation) is the weighted SDF average of voxblox/Furrer et al.: each voxel of
// the model grid takes the observation's trilinearly interpolated distance at T_M_O^-1 * p (only
// where all 8 voxels around that point are observed) and
//   d = (W_M d_M + W_O d_O) / (W_M + W_O),  W = min(W_M + W_O, max_weight),
// colour weighted the same way. New model blocks are allocated where the observation has
// surface the model lacks. The model's voxel size may be finer than the map's
// (ObjectModelConfig::voxel_size_m); the founding observation is then resampled the same way.
//
// Thread safety: value types; free functions without shared state.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"
#include "strata/objects/object_observation.h"

namespace strata::objects {

/// Where a model stood in one session: one matched (or founding) observation.
struct ObjectInstance {
  int session = 0;
  int segment_id = 0;
  Eigen::Isometry3d T_W_M = Eigen::Isometry3d::Identity();  // model frame -> world, that session
  double match_score = 1.0;       // registration fitness x SDF agreement; 1 for the founding one
  float observed_area_m2 = 0.0f;  // surface area of that session's segment
  bool merged = false;            // its voxels were averaged into the model
  /// false: the match's overlap left the horizontal translation open (one face or a top seen
  /// alone, DatabaseConfig::min_horizontal_constraint): the identity holds, T_W_M may be slid
  /// along that face, and the observation was not merged.
  bool pose_constrained = true;
};

struct ObjectModelConfig {
  /// Model voxel edge; 0 = the session map's. Finer costs 8x voxels per halving.
  float voxel_size_m = 0.0f;
  /// Upper bound of a voxel's merged weight (as MapConfig::max_weight).
  float max_weight = 1000.0f;
  /// Voxels with less weight are unobserved for meshing and sampling.
  float min_weight = 1e-3f;
  void validate() const;  // InputError naming the bad field
};

struct ObjectModel {
  int id = 0;                             // 1.. in order of creation, never reused
  TsdfMap tsdf{MapConfig{}};              // in M; truncation as the map's
  std::vector<ObjectInstance> instances;  // in the order they were added
  int merged_observations = 0;
  // Derived from tsdf by refreshModel(): kept so matching does not re-mesh.
  Mesh mesh_M;                                         // marching cubes of tsdf, model frame
  SurfaceCloud surface_M;                              // thinned mesh vertices, for registration
  Eigen::Vector3f extent_m = Eigen::Vector3f::Zero();  // sorted descending
  float surface_area_m2 = 0.0f;
  Eigen::Vector3f mean_color = Eigen::Vector3f::Zero();
};

/// Trilinear interpolation of the TSDF at `p` (map frame, metres): nullopt unless the 8 voxel
/// centres around p are allocated with weight >= min_weight (and > 0). Corners whose trilinear
/// weight is zero are not needed: a p within 1e-4 voxel of a grid plane counts as on it, so a
/// sample at a voxel centre is that voxel, exactly. Returns distance, colour and weight (the
/// minimum of the corners used).
struct TsdfSample {
  float distance_m = 0.0f;
  float weight = 0.0f;
  Eigen::Vector3f color = Eigen::Vector3f::Zero();  // 0..255
};
std::optional<TsdfSample> sampleTsdf(const TsdfMap& map, const Eigen::Vector3f& p,
                                     float min_weight);

/// A new model from its founding observation: M = O (T_W_M = the observation's T_W_O), the TSDF
/// copied (or resampled to config.voxel_size_m), refreshModel() run, one instance added.
ObjectModel foundModel(int id, const ObjectObservation& observation,
                       const ObjectModelConfig& config);

/// Averages `observation` into `model` with T_M_O (observation frame -> model frame), as above.
/// Adds no instance (the database does). Call refreshModel() after.
void mergeObservation(ObjectModel& model, const ObjectObservation& observation,
                      const Eigen::Isometry3d& T_M_O, const ObjectModelConfig& config);

/// Re-meshes the model and recomputes surface_M (spacing `sample_spacing_m`), extent, area and
/// mean colour.
void refreshModel(ObjectModel& model, float sample_spacing_m, const ObjectModelConfig& config);

/// Surface area of a triangle mesh (m^2).
float meshArea(const Mesh& mesh);

}  // namespace strata::objects
