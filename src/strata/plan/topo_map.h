#pragma once
// The topological map (Publication VII, "Topomap"): the traversable voxels (traversability.h,
// the robot sphere free, so the map keeps the clearance) grouped into convex clusters joined by
// portals, a graph a path query searches in a fraction of the grid's time.
//
// Clusters: axis-aligned boxes of traversable voxels, grown greedily from seeds taken in order of
// largest clearance (ESDF distance); a box grows face by face, one voxel layer at a time, while
// the whole new layer is traversable and unclaimed. Every traversable voxel lies in exactly one
// box; a box is convex and entirely traversable, so the straight segment between two points of
// its voxel-centre hull stays over traversable voxels.
// Portals: where two boxes touch face to face (6-adjacent voxels), the shared rectangle, on the
// plane between the two voxel layers; its centre is a graph node. Two portals of one cluster are
// joined by an edge of their straight-line length (edges are implicit: a cluster's portal list).
// Connectivity equals the 6-connectivity of the traversable voxels (grid A*'s).
//
// update(): after the ESDF changed in `changed_blocks` (blocks whose ESDF distance or observed
// flag changed), only the clusters within reach of them (the blocks dilated by the robot radius)
// are dropped; traversability is recomputed in the dilated blocks, the freed voxels regrown into
// boxes, and the portals and lookup rebuilt (cheap, linear in the map's cells). When the map's
// allocated bounds changed, update() rebuilds everything (stats().last_update_full).
// Thread safety: not thread safe; const methods may run concurrently with each other.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/plan/topo_landmarks.h"
#include "strata/plan/traversability.h"

namespace strata::plan {

struct TopoOptions {
  /// The robot sphere the clusters keep free (metres).
  float radius_m = 0.3f;
  UnknownPolicy unknown = UnknownPolicy::kOccupied;
  /// Landmarks of the search's lower bound: more cut more expansions and cost count x portals
  /// floats and a Dijkstra each to build.
  int landmarks = 8;
};

/// Where two clusters touch: the rectangle of crossing points (world frame, metres) on the plane
/// between them (lo_W[axis] == hi_W[axis]); on the other axes it spans the touching voxel
/// centres.
struct TopoPortal {
  std::int32_t a = -1;  // the cluster on the lower side along `axis`
  std::int32_t b = -1;  // the cluster on the upper side
  int axis = 0;
  Eigen::Vector3f lo_W = Eigen::Vector3f::Zero();
  Eigen::Vector3f hi_W = Eigen::Vector3f::Zero();
  Eigen::Vector3f centre() const { return 0.5f * (lo_W + hi_W); }
};

struct TopoStats {
  double build_ms = 0.0;             // the last full build (traversability, boxes, portals)
  double update_ms = 0.0;            // the last update()
  bool last_update_full = false;     // it rebuilt everything
  std::size_t clusters_dropped = 0;  // by the last update
  std::size_t clusters_grown = 0;
  std::size_t voxels_retested = 0;  // sphere tests the last update ran (all cells when full)
  std::size_t traversable_voxels = 0;
  std::size_t grid_cells = 0;  // of the bounds (what a grid over them holds)
};

class TopoMap {
 public:
  /// Builds the map of `esdf` (host sphere tests, esdf_query.h). InputError for a bad radius.
  TopoMap(const EsdfMap& esdf, const TopoOptions& options);

  void update(const EsdfMap& esdf, const std::vector<BlockIndex>& changed_blocks);

  const TopoOptions& options() const { return options_; }
  float voxelSize() const { return voxel_size_m_; }
  const VoxelBox& bounds() const { return bounds_; }
  const std::vector<VoxelBox>& clusters() const { return clusters_; }
  const std::vector<TopoPortal>& portals() const { return portals_; }
  /// portals()[i].centre(), kept for the search.
  const std::vector<Eigen::Vector3f>& portalCentres() const { return portal_centres_; }
  /// Portal ids of cluster c (its graph edges join each pair).
  const std::int32_t* portalsBegin(std::int32_t c) const;
  const std::int32_t* portalsEnd(std::int32_t c) const;
  /// Landmark distances for the search's lower bound (topo_landmarks.h).
  const TopoLandmarks& landmarks() const { return landmarks_; }
  /// Graph distances from portal p to every portal (Dijkstra; infinity where not connected).
  std::vector<float> distancesFrom(std::int32_t p) const;
  /// Graph edges: pairs of portals sharing a cluster.
  std::size_t edgeCount() const;
  /// The cluster holding voxel v, or -1 (not traversable, or outside the bounds).
  std::int32_t clusterAt(const Eigen::Vector3i& v) const;
  /// Connected components of the clusters through portals: one label per cluster, 0..count-1.
  std::vector<std::int32_t> components(std::int32_t* count = nullptr) const;

  const TopoStats& stats() const { return stats_; }
  /// Clusters, portals, the cluster-portal lists and the block lookup (bytes).
  std::size_t memoryBytes() const;

 private:
  void build(const EsdfMap& esdf);
  void rebuildLinks();

  TopoOptions options_;
  float voxel_size_m_ = 0.0f;
  VoxelBox bounds_;
  std::vector<VoxelBox> clusters_;
  std::vector<TopoPortal> portals_;
  std::vector<Eigen::Vector3f> portal_centres_;
  TopoLandmarks landmarks_;
  std::vector<std::int32_t> portal_offsets_;  // per cluster, into portal_ids_ (CSR)
  std::vector<std::int32_t> portal_ids_;
  std::unordered_map<BlockIndex, std::vector<std::int32_t>, BlockIndexHash> block_clusters_;
  TopoStats stats_;
};

}  // namespace strata::plan
