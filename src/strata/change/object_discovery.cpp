// Object discovery: the pipeline of steps described in objects.h.
#include "strata/change/object_discovery.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/change/change_detector.h"
#include "strata/change/internal/objects_steps.h"
#include "strata/change/region_growing.h"
#include "strata/core/error.h"
#include "strata/mesh/extract_mesh.h"

namespace strata::change {
namespace {

void requireInRange(float value, float lo, float hi, const char* field) {
  if (!std::isfinite(value) || value < lo || value > hi) {
    throw InputError(std::string("invalid object config: ") + field + " must be in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                     std::to_string(value));
  }
}

/// Faces of each component, in face order.
std::vector<std::vector<std::uint32_t>> facesByComponent(const Components& components) {
  std::vector<std::vector<std::uint32_t>> faces(components.count);
  for (std::size_t f = 0; f < components.component.size(); ++f) {
    if (components.component[f] >= 0) {
      faces[static_cast<std::size_t>(components.component[f])].push_back(
          static_cast<std::uint32_t>(f));
    }
  }
  return faces;
}

/// Meshes of the components that are neither planar nor small.
std::vector<Mesh> keptSegments(const Mesh& mesh, const Components& components,
                               const ObjectConfig& config, ObjectStats& stats) {
  std::vector<Mesh> kept;
  for (const auto& faces : facesByComponent(components)) {
    Mesh segment = detail::subMesh(mesh, faces);
    if (segment.vertices.size() < config.min_vertices) {
      ++stats.dropped_small;
    } else if (detail::singularValueRatio(segment) < config.min_singular_value_ratio) {
      ++stats.dropped_planar;
    } else {
      kept.push_back(std::move(segment));
    }
  }
  // Largest first; stable, so equal sizes keep the order of their lowest face (deterministic).
  std::stable_sort(kept.begin(), kept.end(), [](const Mesh& a, const Mesh& b) {
    return a.vertices.size() > b.vertices.size();
  });
  return kept;
}

std::size_t countTrue(const std::vector<bool>& flags) {
  return static_cast<std::size_t>(std::count(flags.begin(), flags.end(), true));
}

}  // namespace

void ObjectConfig::validate() const {
  if (!std::isfinite(mesh_min_weight) || mesh_min_weight <= 0.0f) {
    throw InputError("invalid object config: mesh_min_weight must be finite and positive");
  }
  requireInRange(vertex_dynamic_vote, 1e-3f, 1.0f, "vertex_dynamic_vote");
  requireInRange(region_neighbour_angle_deg, 0.0f, 180.0f, "region_neighbour_angle_deg");
  requireInRange(region_mean_angle_deg, 0.0f, 180.0f, "region_mean_angle_deg");
  requireInRange(region_dynamic_share, 0.0f, 1.0f, "region_dynamic_share");
  requireInRange(component_merge_gap_voxels, 0.0f, 10.0f, "component_merge_gap_voxels");
  requireInRange(min_singular_value_ratio, 0.0f, 1.0f, "min_singular_value_ratio");
  if (min_vertices < 3) throw InputError("invalid object config: min_vertices must be >= 3");
}

std::vector<DiscoveredObject> extractObjects(const TsdfMap& session_map,
                                             const LabelMap& session_dynamic,
                                             const ObjectConfig& config, int session,
                                             ObjectStats* stats, LabelledSurface* surface) {
  config.validate();
  if (std::abs(session_map.config().voxel_size_m - session_dynamic.voxel_size_m) > 1e-6f) {
    throw InputError("extractObjects: the labels' voxel size (" +
                     std::to_string(session_dynamic.voxel_size_m) + " m) differs from the map's (" +
                     std::to_string(session_map.config().voxel_size_m) + " m)");
  }
  MeshOptions mesh_options;
  mesh_options.min_weight = config.mesh_min_weight;
  Mesh mesh = extractMesh(session_map, mesh_options);
  ObjectStats local;
  local.faces = mesh.triangles.size();
  const std::vector<bool> labelled = detail::labelFaces(
      mesh, detail::labelVertices(mesh, session_dynamic, config.vertex_dynamic_vote));
  local.dynamic_faces_labelled = countTrue(labelled);
  const FaceAdjacency adjacency = buildFaceAdjacency(mesh);
  const Regions regions = growSmoothRegions(mesh, adjacency, config.region_neighbour_angle_deg,
                                            config.region_mean_angle_deg);
  local.regions = regions.count;
  std::vector<bool> dynamic = labelRegions(regions, labelled, config.region_dynamic_share);
  local.dynamic_faces_refined = countTrue(dynamic);
  const Components components =
      mergeNearbyComponents(mesh, connectedComponents(adjacency, dynamic),
                            config.component_merge_gap_voxels * session_map.config().voxel_size_m);
  local.components = components.count;
  std::vector<DiscoveredObject> objects;
  for (Mesh& segment : keptSegments(mesh, components, config, local)) {
    objects.push_back(detail::makeObject(std::move(segment), session));
    objects.back().id = static_cast<int>(objects.size());
  }
  if (stats != nullptr) *stats = local;
  if (surface != nullptr) *surface = LabelledSurface{std::move(mesh), std::move(dynamic)};
  return objects;
}

std::vector<DiscoveredObject> sessionObjects(ChangeDetector& detector, int session,
                                             const ObjectConfig& config, TsdfMap* session_map,
                                             LabelledSurface* surface) {
  TsdfMap map = detector.sessionMap(session);
  std::vector<DiscoveredObject> objects = extractObjects(
      map, detector.sessionDynamic(session), config, session, nullptr, surface);
  if (session_map != nullptr) *session_map = std::move(map);
  return objects;
}

}  // namespace strata::change
