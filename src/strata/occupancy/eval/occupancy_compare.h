#pragma once
// The occupancy layer against the TSDF on the same frames, both against the true scene, as the
// thesis compared them: surface position error (occupied voxel centres / TSDF mesh vertices: |true
// signed distance|) and completeness (share of true surface points within one voxel of an
// occupied voxel centre / of the TSDF mesh). One DeviceFusion; the occupancy layer shares its map.
#include <cstddef>
#include <functional>
#include <string>

#include "strata/mapper/eval/accuracy.h"
#include "strata/io/open_dataset.h"
#include "strata/occupancy/occupancy_config.h"
#include "strata/occupancy/occupancy_map.h"
#include "strata/map/map_config.h"
#include "strata/mesh/mesh.h"
#include "strata/vk/vk.h"

namespace strata::eval {

/// Distances of a point set to the true surface, metres.
struct SurfaceError {
  std::size_t count = 0;
  double mean_m = 0.0;
  double median_m = 0.0;
  double p95_m = 0.0;
};
/// |truth(p)| over `points`.
SurfaceError surfaceError(const std::vector<Eigen::Vector3f>& points, const TrueSdf& truth);

struct OccupancyComparisonSetup {
  MapConfig map;              // the TSDF's; the occupancy layer uses its voxels and depth range
  OccupancyConfig occupancy;  // see OccupancyConfig::forMap
  std::size_t frames = 0;     // first n frames of the dataset (0 = all)
  /// Every n-th pixel of the exact depth (from (1, 1)) becomes a true surface point.
  int truth_pixel_stride = 4;
  /// Also run the C++ reference on every frame (time per frame, agreement with the device).
  bool run_reference = false;
  /// Non-empty: also write <prefix>occupancy.ply (occupied voxels as cubes) and <prefix>tsdf.ply.
  std::string ply_prefix;
};

/// Frame i as the ground truth sees it: exact depth (0 = no surface) and the true pose.
using TruthFrame = std::function<RgbdFrame(std::size_t)>;

struct OccupancyTsdfComparison {
  std::size_t frames = 0;
  std::size_t truth_points = 0;  // true surface points within the sensor's depth range
  std::size_t occupied_voxels = 0;
  std::size_t free_voxels = 0;
  std::size_t mesh_vertices = 0;
  SurfaceError occupancy_error;         // occupied voxel centres
  SurfaceError tsdf_error;              // TSDF mesh vertices
  double occupancy_completeness = 0.0;  // within one voxel of an occupied voxel centre
  double tsdf_completeness = 0.0;       // within one voxel of the TSDF mesh
  double occupancy_device_ms = 0.0;     // per frame, device time (timestamps), frame 0 left out
  double occupancy_allocate_ms = 0.0;   // its passes: allocation, mark, update (per frame)
  double occupancy_mark_ms = 0.0;
  double occupancy_update_ms = 0.0;
  std::size_t exact_fallbacks = 0;         // frames whose block walk missed a block (all frames)
  double fusion_device_ms = 0.0;           // TSDF allocation + integration per frame, same frames
  double reference_ms = 0.0;               // C++ reference per frame (run_reference only)
  OccupancyAgreement device_vs_reference;  // run_reference only
};

/// Fuses `dataset`'s frames into a TSDF and the occupancy layer on the device, extracts the mesh,
/// and measures both against `truth` (signed distance) and `truth_frame` (surface points).
/// Throws InputError for a bad setup.
OccupancyTsdfComparison compareOccupancyWithTsdf(vk::Context& context, const Dataset& dataset,
                                                 const TruthFrame& truth_frame,
                                                 const TrueSdf& truth,
                                                 const OccupancyComparisonSetup& setup);

/// Points of the true surface seen by `frame` (exact depth in [min_depth_m, max_depth_m]), every
/// stride-th pixel from (1, 1) (from (0, 0) when stride is 1).
std::vector<Eigen::Vector3f> trueSurfacePoints(const RgbdFrame& frame,
                                               const CameraIntrinsics& intrinsics, int stride,
                                               float min_depth_m, float max_depth_m);

/// Occupied voxels as closed cubes (12 triangles each), for viewing beside the TSDF mesh.
Mesh occupiedVoxelMesh(const OccupancyMap& map, const OccupancyLogOdds& l);

}  // namespace strata::eval
