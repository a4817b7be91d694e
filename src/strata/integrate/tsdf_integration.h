#pragma once
// Kernel 2, projective TSDF integration. Device: shaders/integrate_tsdf.comp, dispatched by
// DeviceFusion. This file is the C++ reference: the readable specification of the update.
#include <cmath>
#include <vector>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/map/map_config.h"
#include "strata/map/tsdf_map.h"

namespace strata {

/// Observed RGB of a pixel packed as r | g << 8 | b << 16 (0 when there is no colour image).
std::uint32_t packedPixelColor(const ColorImage& color, int u, int v);

/// One voxel's update from one frame (the rule of integrate_tsdf.comp):
/// project the voxel centre p_W into the depth image (nearest pixel); skip if outside, behind the
/// camera or the depth is invalid/out of range; skip if the distance along the ray
/// (depth - z) * |ray| is below -truncation; sdf = distance to the plane of the observed point
/// (config.distance_mode kPointToPlane, where the pixel's normal is valid) or along the ray; tsdf =
/// min(sdf, truncation); weight 1 or 1/depth^2, times a linear drop-off behind the surface; running
/// weighted average of tsdf and colour; weight clamp.
void integrateVoxelReference(TsdfVoxel& voxel, const Eigen::Vector3f& p_W, const DepthImage& depth,
                             const std::vector<Eigen::Vector4f>* normals_C, const ColorImage* color,
                             const FrameCamera& camera, const MapConfig& config);

/// integrateVoxelReference in two steps, for callers that look at one frame's observation before
/// blending it (change/skipped_keyframe_evidence.h): what the frame says of the voxel, then the blend.
struct VoxelObservation {
  /// Measured depth beyond the voxel along its pixel's ray (the band test's distance); NaN where
  /// the voxel does not project into the image or its pixel has no valid depth.
  float ray_sdf_m = NAN;
  float tsdf_m = 0.0f;
  float weight = 0.0f;  // 0: no update (no depth, or more than the truncation behind it)
  int u_px = -1;        // the pixel, where ray_sdf_m is a number
  int v_px = -1;
};
VoxelObservation observeVoxelReference(const Eigen::Vector3f& p_W, const DepthImage& depth,
                                       const std::vector<Eigen::Vector4f>* normals_C,
                                       const FrameCamera& camera, const MapConfig& config);
/// The running weighted average of tsdf and colour, and the weight clamp; nothing at weight 0.
void applyObservation(TsdfVoxel& voxel, const VoxelObservation& observation,
                      const ColorImage* color, const MapConfig& config);

/// Whole frame on the host: allocate the blocks (allocatedBlocksReference) and update all
/// their voxels. Returns the touched blocks. Uses up to `threads` threads over blocks.
std::vector<BlockIndex> integrateFrameReference(TsdfMap& map, const RgbdFrame& frame,
                                                const CameraIntrinsics& intrinsics,
                                                int threads = 2);

}  // namespace strata
