#pragma once
// Parameters of a TSDF map and its fusion. Defaults: 2 cm voxels, truncation of 4 voxels.
// validate() is called once by every consumer and throws InputError naming the field.
#include <cstdint>
#include <string>

namespace strata {

enum class DistanceMode : std::uint32_t {
  kAlongRay = 0,      // (depth - z) * |ray|: the classic projective distance (KinectFusion, Open3D)
  kPointToPlane = 1,  // distance to the plane of the observed surface (normal from the depth
                      // image): exact for planes at any viewing angle, where the distance along
                      // the ray overestimates by 1/cos(angle); falls back to kAlongRay at
                      // depth discontinuities
};

enum class WeightMode : std::uint32_t {
  kConstant = 0,          // every observation weighs 1
  kInverseDepthSquared = 1,  // weight 1/z^2 (metres): near, less noisy depth counts more
};

struct MapConfig {
  /// Edge of a voxel. Smaller is finer and costs 8x memory per halving.
  float voxel_size_m = 0.02f;
  /// Truncation band half-width in voxels (distance = truncation_voxels * voxel_size_m). Wider bands
  /// are smoother and fill holes but blur thin structures.
  float truncation_voxels = 4.0f;
  /// Upper bound of a voxel's accumulated weight: lower reacts faster to change, higher averages more.
  float max_weight = 100.0f;
  /// Depth samples outside [min_depth_m, max_depth_m] are ignored (sensor's reliable range).
  float min_depth_m = 0.1f;
  float max_depth_m = 5.0f;
  /// 1/z^2 by default: structured-light depth noise grows with z^2, so near samples deserve more.
  WeightMode weight_mode = WeightMode::kInverseDepthSquared;
  DistanceMode distance_mode = DistanceMode::kPointToPlane;
  /// Depth normals are invalid where a neighbour pixel differs by more than this share of the
  /// depth (a discontinuity): smaller keeps silhouettes sharp, larger accepts steeper planes.
  float normal_max_relative_jump = 0.05f;
  /// Behind the surface, from dropoff_start_voxels on, the weight falls linearly to 0 at the end of
  /// the band: the space behind a surface is seen less reliably than the space in front of it.
  bool weight_dropoff = true;
  float dropoff_start_voxels = 1.0f;
  /// Initial capacities; both grow on demand (pool by reallocation, hash by rehash).
  std::uint32_t initial_block_capacity = 8192;
  std::uint32_t initial_hash_capacity = 1u << 16;  // power of two
  /// Also allocate (and so observe) the free space between the camera and the surfaces, on a
  /// sparse pixel grid: the ESDF then covers free space, not just the truncation band. Costs
  /// blocks (memory) and allocation time; planners want it, surface reconstruction does not.
  bool allocate_free_space = false;
  /// Every n-th pixel on both axes allocates its free space (blocks are 8 voxels wide).
  std::uint32_t free_space_pixel_stride = 4;
  /// Device memory budget in blocks (6 KiB each); 0 = as many as one allocation on the device holds.
  /// Fusion stops with an error naming the blocks asked for when a frame needs more.
  std::uint32_t max_block_capacity = 0;

  float truncationDistance() const { return truncation_voxels * voxel_size_m; }
  float blockSize() const;
  /// Throws InputError naming the bad field.
  void validate() const;
  std::string describe() const;
};

}  // namespace strata
