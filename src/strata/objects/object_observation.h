#pragma once
// One discovered segment of one session turned into an object observation: a small TSDF of its
// own in an object frame, plus the surface samples registration works on (docs/objects.md).
//
// Object frame O of an observation: origin at the segment's centroid (mean of its mesh vertices),
// axes parallel to the world's, so T_W_O is a pure translation. Its TSDF holds the voxels of the
// session map whose nearest surface is the segment's: a voxel of the session map is kept when it
// lies within `band_voxels` of a vertex of the segment and no vertex of the rest of the session's
// surface (floor, walls, other objects) is nearer to it. That keeps the object's truncation band
// on every observed side and leaves the floor it stands on out of the model. Voxels are copied
// unchanged (distance, weight, colour), re-indexed in O's grid (same voxel size: the translation
// is rounded to whole voxels, so no resampling blurs a single observation).
//
// Thread safety: free functions, no shared state.
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/change/object_discovery.h"
#include "strata/map/tsdf_map.h"

namespace strata::objects {

/// Surface samples of a shape in one frame: points with unit normals and colours.
struct SurfaceCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;            // same size as points, unit length
  std::vector<std::array<std::uint8_t, 3>> colors;  // empty or same size as points
  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
};

struct ObservationConfig {
  /// Voxels of the session map within this many voxels of a segment vertex are candidates for
  /// the object's TSDF (the truncation band is 4 voxels by default).
  float band_voxels = 4.0f;
  /// Surface samples for registration: the segment's vertices thinned to one per cube of this
  /// many voxels (1 = about one sample per voxel of surface).
  float sample_spacing_voxels = 1.0f;
  /// Segments with fewer surface samples (after thinning) are degenerate and refused.
  std::size_t min_samples = 60;
  /// Segments whose smallest / largest singular value of the centred samples is below this are
  /// planar and refused (a patch of wall cannot be registered in 6 DoF).
  float min_singular_value_ratio = 0.05f;
  /// Throws InputError naming the bad field.
  void validate() const;
};

struct ObjectObservation {
  int session = 0;
  int segment_id = 0;                                     // DiscoveredObject::id in its session
  Eigen::Isometry3d T_W_O = Eigen::Isometry3d::Identity();  // object frame -> world
  TsdfMap tsdf{MapConfig{}};                              // in O, the session map's voxel size
  SurfaceCloud surface_O;                                 // thinned mesh vertices, in O
  Eigen::Vector3f extent_m = Eigen::Vector3f::Zero();     // bounding box of surface_O, sorted descending
  float surface_area_m2 = 0.0f;                           // of the segment's mesh
  Eigen::Vector3f mean_color = Eigen::Vector3f::Zero();   // 0..255 per channel
};

/// Builds the observation of `segment` (world frame) from its session's own TSDF layer and the
/// session's whole labelled surface (change::extractObjects' `surface`; its mesh must be the one
/// the segment's faces were taken from). Throws InputError for a degenerate segment (too few
/// samples, planar: the message says which and the numbers) or a config that does not validate.
ObjectObservation observeObject(const TsdfMap& session_map, const change::LabelledSurface& surface,
                                const change::DiscoveredObject& segment, int session,
                                const ObservationConfig& config = {});

/// Thins a mesh's vertices (with normals and colours; normals are recomputed from the faces when
/// the mesh has none) to at most one sample per cube of `spacing_m`, keeping the sample nearest
/// each cube's centre. Deterministic.
SurfaceCloud sampleSurface(const Mesh& mesh, float spacing_m);

}  // namespace strata::objects
