#pragma once
// Evaluation of change detection against ground truth (tests): discovered objects against
// the objects that moved, and the static map against the static world.
//
// Object discovery, per session. A moved object counts as found when one discovered segment covers
// >= found_min_coverage of its visible surface (share of its seen points within match_distance_m
// of the segment) and lies >= found_min_on_object on it (share of the segment's area within
// match_distance_m of the object's true surface). A segment is true when it lies mostly
// (>= segment_min_on_object) on one moved object, else a false positive. precision = true
// segments / segments; recall = found / moved objects with enough visible surface.
// Over-segmented: a moved object that two or more true segments lie on. Under-segmented: a
// segment lying >= under_segment_min_share on each of two or more objects.
//
// Static map: completeness = share of the static surface any session saw (visible points of the
// static structure and of objects that never changed) within static_tolerance_m of the static
// mesh; ghosts = share of the static mesh's area on a moved object (within match_distance_m of
// one of its poses) and not on the static truth.
#include <cstddef>
#include <string>
#include <vector>

#include "strata/change/object_discovery.h"
#include "strata/mesh/mesh.h"

namespace strata::change {

struct EvaluationConfig {
  /// A point lies on a surface within this distance: the fused mesh's error plus the bevel
  /// marching cubes puts on edges (about a voxel); 2 voxels at 2 cm.
  float match_distance_m = 0.04f;
  float found_min_coverage = 0.5f;   // target: 50 %
  float found_min_on_object = 0.8f;  // target: 80 %
  float segment_min_on_object = 0.5f;
  float under_segment_min_share = 0.2f;
  /// Moved objects with less seen surface (points x spacing^2) are left out of the recall: a
  /// glimpse at a frame's edge is not enough to map an object.
  float min_visible_area_m2 = 0.01f;
  /// Static surface within this of the static mesh counts as reconstructed (target: 2 cm).
  float static_tolerance_m = 0.02f;
  /// A surface point counts as seen by a session when at least this many of its frames saw it.
  /// With constant fusion weights set it to the change detector's min_weight: a voxel seen in
  /// fewer frames is unobserved there, so neither an object nor the static map can show it.
  int min_views = 1;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// One object of the ground truth in one session, world frame.
struct TruthObject {
  int id = 0;
  std::string name;
  bool moved = false;  // dynamic in this session (evaluated); false: present and unchanged
  Mesh mesh;           // its true surface at its pose in the session
  std::vector<Eigen::Vector3f> visible_points;  // what the session saw of it
  float visible_area_m2 = 0.0f;
};

struct ObjectMatch {
  int object_id = 0;
  std::string name;
  float visible_area_m2 = 0.0f;
  bool evaluated = false;  // moved, and enough visible surface
  bool found = false;
  int best_segment = 0;    // id of the segment matching it best (0: none touches it)
  double coverage = 0.0;   // of the best segment
  double on_object = 0.0;  // of the best segment
  int segments = 0;        // true segments lying on it (2+: over-segmented)
};

struct SegmentMatch {
  int segment_id = 0;
  int object_id = 0;  // the moved object it lies on (0: none: a false positive)
  double on_object = 0.0;
  bool under_segmented = false;
  std::size_t vertices = 0;
};

struct ObjectCounts {
  std::size_t moved = 0;  // evaluated moved objects
  std::size_t found = 0;
  std::size_t segments = 0;
  std::size_t true_segments = 0;
  std::size_t false_positives = 0;
  std::size_t over_segmented = 0;   // objects
  std::size_t under_segmented = 0;  // segments
  double precision() const { return segments ? double(true_segments) / double(segments) : 1.0; }
  double recall() const { return moved ? double(found) / double(moved) : 1.0; }
  ObjectCounts& operator+=(const ObjectCounts& o);
};

struct SessionObjectEvaluation {
  int session = 0;
  std::vector<ObjectMatch> objects;  // moved objects, by id
  std::vector<SegmentMatch> segments;
  ObjectCounts counts;
};

/// `truth`: every object present in the session (moved or not); `segments`: its discovered objects.
SessionObjectEvaluation evaluateObjects(int session, const std::vector<TruthObject>& truth,
                                        const std::vector<DiscoveredObject>& segments,
                                        const EvaluationConfig& config);

struct StaticMapEvaluation {
  std::size_t seen_points = 0;  // static surface samples seen by some session
  double completeness = 0.0;    // share within static_tolerance_m of the static mesh
  double mesh_area_m2 = 0.0;    // static mesh
  double ghost_area_m2 = 0.0;   // of it on moved objects
  double ghostShare() const { return mesh_area_m2 > 0 ? ghost_area_m2 / mesh_area_m2 : 0.0; }
};

/// `static_truth`: the static world and the objects that never changed; `moved_truth`: every pose
/// of every object that changed; `seen_static`: static surface points seen by any session.
StaticMapEvaluation evaluateStaticMap(const Mesh& static_mesh, const Mesh& static_truth,
                                      const std::vector<Mesh>& moved_truth,
                                      const std::vector<Eigen::Vector3f>& seen_static,
                                      const EvaluationConfig& config);

/// "precision 100.0 % (12/12), recall 95.2 % (20/21), over-segmented 1, under-segmented 0".
std::string describeCounts(const ObjectCounts& counts);

}  // namespace strata::change
