#include "strata/core/clock.h"
#include "strata/occupancy/eval/occupancy_compare.h"

#include <algorithm>
#include <chrono>

#include "strata/core/error.h"
#include "strata/occupancy/eval/occupancy_nearest.h"
#include "strata/integrate/device_fusion.h"
#include "strata/occupancy/occupancy_device.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/mesh/ply.h"

namespace strata::eval {
namespace {

template <typename Grid>
double shareWithin(const std::vector<Eigen::Vector3f>& points, const Grid& grid) {
  if (points.empty()) return 0.0;
  std::size_t within = 0;
  for (const Eigen::Vector3f& p : points) within += std::isfinite(grid.nearestWithin(p)) ? 1 : 0;
  return static_cast<double>(within) / static_cast<double>(points.size());
}

void validateSetup(const Dataset& dataset, const OccupancyComparisonSetup& setup) {
  setup.map.validate();
  setup.occupancy.validate();
  if (setup.truth_pixel_stride <= 0) {
    throw InputError("occupancy comparison: truth_pixel_stride must be positive");
  }
  if (dataset.size() == 0)
    throw InputError("occupancy comparison: " + dataset.name() + " is empty");
}

/// Everything measured while the frames go in.
struct FusedFrames {
  std::vector<Eigen::Vector3f> truth_points;
  double occupancy_ms = 0.0, fusion_ms = 0.0, reference_ms = 0.0;
  double allocate_ms = 0.0, mark_ms = 0.0, update_ms = 0.0;
  std::size_t timed = 0;
  std::size_t exact_fallbacks = 0;
};

void fuseFrames(const Dataset& dataset, const TruthFrame& truth_frame,
                const OccupancyComparisonSetup& setup, std::size_t frames, DeviceFusion& fusion,
                DeviceOccupancy& occupancy, OccupancyMap& reference, FusedFrames& out) {
  const CameraIntrinsics in = dataset.intrinsics();
  for (std::size_t i = 0; i < frames; ++i) {
    const RgbdFrame frame = dataset.load(i);
    const FrameStats fused = fusion.integrate(frame, in);
    const OccupancyFrameStats occupied = occupancy.integrate(frame, in);
    out.exact_fallbacks += occupied.exact_fallbacks;
    if (setup.run_reference) {
      const auto start = std::chrono::steady_clock::now();
      integrateOccupancyReference(frame.depth, FrameCamera::from(in, frame.T_W_C), setup.occupancy,
                                  reference);
      if (i > 0) out.reference_ms += msSince(start);
    }
    if (i > 0 || frames == 1) {  // frame 0 grows every buffer from empty
      out.occupancy_ms += occupied.deviceMs();
      out.allocate_ms += occupied.allocate_ms;
      out.mark_ms += occupied.mark_ms;
      out.update_ms += occupied.update_ms;
      out.fusion_ms += fused.upload_ms + fused.normals_ms + fused.allocate_ms + fused.integrate_ms;
      ++out.timed;
    }
    const std::vector<Eigen::Vector3f> points =
        trueSurfacePoints(truth_frame(i), in, setup.truth_pixel_stride, setup.map.min_depth_m,
                          setup.occupancy.max_range_m);
    out.truth_points.insert(out.truth_points.end(), points.begin(), points.end());
  }
}

}  // namespace

SurfaceError surfaceError(const std::vector<Eigen::Vector3f>& points, const TrueSdf& truth) {
  SurfaceError e;
  e.count = points.size();
  if (points.empty()) return e;
  std::vector<double> d;
  d.reserve(points.size());
  for (const Eigen::Vector3f& p : points) d.push_back(std::abs(truth(p.cast<double>())));
  std::sort(d.begin(), d.end());
  double sum = 0.0;
  for (const double x : d) sum += x;
  e.mean_m = sum / static_cast<double>(d.size());
  e.median_m = d[d.size() / 2];
  e.p95_m =
      d[std::min(d.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(d.size())))];
  return e;
}

OccupancyTsdfComparison compareOccupancyWithTsdf(vk::Context& context, const Dataset& dataset,
                                                 const TruthFrame& truth_frame,
                                                 const TrueSdf& truth,
                                                 const OccupancyComparisonSetup& setup) {
  validateSetup(dataset, setup);
  const std::size_t frames =
      setup.frames == 0 ? dataset.size() : std::min(setup.frames, dataset.size());
  DeviceFusion fusion(context, setup.map);
  DeviceOccupancy occupancy(fusion.map(), setup.occupancy);  // shares the fusion's block index
  OccupancyMap reference(setup.map.voxel_size_m);
  FusedFrames fused;
  fuseFrames(dataset, truth_frame, setup, frames, fusion, occupancy, reference, fused);

  OccupancyTsdfComparison out;
  out.frames = frames;
  out.truth_points = fused.truth_points.size();
  const double timed = static_cast<double>(std::max<std::size_t>(fused.timed, 1));
  out.occupancy_device_ms = fused.occupancy_ms / timed;
  out.occupancy_allocate_ms = fused.allocate_ms / timed;
  out.occupancy_mark_ms = fused.mark_ms / timed;
  out.occupancy_update_ms = fused.update_ms / timed;
  out.exact_fallbacks = fused.exact_fallbacks;
  out.fusion_device_ms = fused.fusion_ms / timed;
  out.reference_ms = frames > 1 ? fused.reference_ms / static_cast<double>(frames - 1) : 0.0;

  const OccupancyLogOdds l = setup.occupancy.logOdds();
  OccupancyMap device(setup.map.voxel_size_m);
  occupancy.download(device);
  if (setup.run_reference) out.device_vs_reference = compareOccupancy(device, reference, l, 1e-5f);
  const OccupancyCounts counts = countOccupancy(device, l);
  out.free_voxels = counts.free;
  const std::vector<Eigen::Vector3f> centres = occupiedVoxelCentres(device, l);
  out.occupied_voxels = centres.size();
  TsdfMap tsdf(setup.map);
  fusion.map().download(tsdf);
  const Mesh mesh = extractMesh(tsdf);
  out.mesh_vertices = mesh.vertices.size();

  if (!setup.ply_prefix.empty()) {
    writePly(setup.ply_prefix + "occupancy.ply", occupiedVoxelMesh(device, l));
    writePly(setup.ply_prefix + "tsdf.ply", mesh);
  }
  out.occupancy_error = surfaceError(centres, truth);
  out.tsdf_error = surfaceError(mesh.vertices, truth);
  const float one_voxel_m = setup.map.voxel_size_m;
  out.occupancy_completeness = shareWithin(fused.truth_points, PointGrid(centres, one_voxel_m));
  out.tsdf_completeness = shareWithin(fused.truth_points, TriangleGrid(mesh, one_voxel_m));
  return out;
}

}  // namespace strata::eval
