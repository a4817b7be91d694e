#pragma once
// Keyframe surface descriptors for place recognition without texture: from the keyframe's depth
// image alone, a downsampled cloud with normals, FPFH descriptors (Rusu et al. 2009, PCL) at its
// non-planar points (the keypoints, used to register two keyframes), and one global descriptor per
// keyframe (used to rank candidates): the mean keypoint FPFH, the distribution of distances between
// cloud points (Osada et al.'s D2 shape distribution) and the distribution of ranges, each a
// histogram normalised to sum 1. All three are invariant to the camera's rotation and position.
// Frames: C is the keyframe's camera (x right, y down, z forward), metres.
// Thread safety: free functions, no shared state.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "strata/core/types.h"

namespace strata::align {

using Fpfh = std::array<float, 33>;

struct SurfaceConfig {
  int stride_px = 4;               // depth pixels sampled in u and v before downsampling
  float voxel_m = 0.05f;           // voxel grid of the downsampled cloud
  float min_depth_m = 0.1f;        // depths outside [min, max] are left out
  float max_depth_m = 6.0f;
  float normal_radius_m = 0.12f;   // neighbourhood of the normals (and the surface variation)
  float fpfh_radius_m = 0.30f;     // FPFH support; wider is more distinctive and slower
  /// Points whose surface variation (smallest eigenvalue / sum of the neighbourhood's covariance)
  /// is below this are planar: their FPFH is the same everywhere and they are no keypoints.
  float min_keypoint_variation = 0.01f;
  int max_keypoints = 500;         // an even stride through the non-planar points
  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// One keyframe's surface: keypoints with FPFH (index-aligned) and the global descriptor.
struct KeyframeSurface {
  std::vector<Eigen::Vector3f> keypoints_C_m;
  std::vector<Fpfh> fpfh;
  std::vector<float> global;   // empty when the depth image has too few points
  std::size_t size() const { return keypoints_C_m.size(); }
};

/// Describes the surface a depth image sees. InputError when the image's size disagrees with the
/// intrinsics; an image with few valid depths gives an empty description (no keypoints).
KeyframeSurface describeSurface(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                                const SurfaceConfig& config);

/// Distance between two global descriptors (L1 over the three normalised histograms, 0 to 6);
/// +infinity when either is empty.
double surfaceDistance(const KeyframeSurface& a, const KeyframeSurface& b);

}  // namespace strata::align
