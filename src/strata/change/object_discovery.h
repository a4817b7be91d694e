#pragma once
// Object discovery (docs/change.md, step 6): the parts of one session's surface that
// moved, each as its own mesh.
//
// Steps (object_discovery.cpp): mesh the session map (marching cubes) -> label every vertex from the
// session's dynamic voxel labels (trilinear vote of the 8 voxels around it) -> label faces by their
// vertices -> segment the mesh into smooth regions by the normals of adjacent faces and give each
// region one label (dynamic when more than `region_dynamic_share` of its faces are) -> split the
// dynamic faces into edge-connected components -> drop planar components (leftover pieces of
// floor and wall) and small ones (noise).
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "strata/change/change_types.h"
#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"

namespace strata::change {

struct ObjectConfig {
  /// Voxels of the session map with less weight produce no surface. Low keeps every surface the
  /// session saw (labels decide what moved); higher hides surfaces seen once.
  float mesh_min_weight = 1e-3f;
  /// A vertex is dynamic when at least this share of the trilinear weight of the 8 voxels around
  /// it is dynamic. Lower grows objects into their surroundings, higher erodes their rims.
  float vertex_dynamic_vote = 0.5f;
  /// Adjacent faces join one smooth region when their normals differ by less than this. Lower
  /// fragments noisy surfaces, higher lets regions leak around rounded edges.
  float region_neighbour_angle_deg = 25.0f;
  /// ... and the face's normal differs from the region's mean normal by less than this, so a
  /// region cannot bend slowly from the floor up an object's side.
  float region_mean_angle_deg = 40.0f;
  /// A region becomes dynamic when more than this share of its faces are dynamic, else static
  /// (25 %, the thesis' setting).
  float region_dynamic_share = 0.25f;
  /// Dynamic components closer than this (vertex to vertex, in voxels; 6 cm at 2 cm) are one
  /// object: thin parts (shelf boards, chair legs about a voxel thick) often lose their mesh
  /// connection to the rest. Higher joins objects standing that close; 0 keeps strict mesh
  /// connectivity.
  float component_merge_gap_voxels = 3.0f;
  /// Components whose smallest / largest singular value of the centred vertex positions is below
  /// this are planar (pieces of floor or wall) and dropped. Higher also drops objects seen mostly
  /// from one flat side (a shelf seen from its back panel).
  float min_singular_value_ratio = 0.02f;
  /// Components with fewer vertices are noise and dropped (100 vertices at 2 cm voxels are about
  /// 0.04 m^2 of surface).
  std::size_t min_vertices = 100;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// One moved part of a session's surface.
struct DiscoveredObject {
  int id = 0;       // 1.. within its session, largest first
  int session = 0;  // as passed to extractObjects
  Mesh mesh;        // its faces of the session mesh (world frame), with normals and colours
  Eigen::AlignedBox3f bbox;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // mean of the vertices
  std::size_t vertex_count = 0;
};

/// What the steps did, for reports and tests.
struct ObjectStats {
  std::size_t faces = 0;
  std::size_t dynamic_faces_labelled = 0;  // from the voxel labels
  std::size_t regions = 0;
  std::size_t dynamic_faces_refined = 0;  // after region growing
  std::size_t components = 0;
  std::size_t dropped_planar = 0;
  std::size_t dropped_small = 0;
};

/// The session's surface and the label of each face after region growing (for pictures).
struct LabelledSurface {
  Mesh mesh;
  std::vector<bool> face_dynamic;
};

/// Discovers the objects of one session. `session_map` is the session's own TSDF layer M_i,
/// `session_dynamic` its dynamic part (same voxel size). Throws InputError on a bad config or
/// voxel sizes that disagree. Deterministic. Thread safe for concurrent calls.
std::vector<DiscoveredObject> extractObjects(const TsdfMap& session_map,
                                             const LabelMap& session_dynamic,
                                             const ObjectConfig& config, int session = 0,
                                             ObjectStats* stats = nullptr,
                                             LabelledSurface* surface = nullptr);

class ChangeDetector;

/// The objects of an ended session of `detector` against its current static map: downloads the
/// session's map and dynamic part (explicit device->host copies) and runs extractObjects.
/// `session_map` and `surface` (optional) receive the downloaded map and the labelled surface.
std::vector<DiscoveredObject> sessionObjects(ChangeDetector& detector, int session,
                                             const ObjectConfig& config = {},
                                             TsdfMap* session_map = nullptr,
                                             LabelledSurface* surface = nullptr);

}  // namespace strata::change
