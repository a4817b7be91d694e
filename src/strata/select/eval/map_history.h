#pragma once
// What a map was built from, for the ground truth of keyframe selection: per finished
// session, the simulated world of that session and the places its fused keyframes saw. A keyframe
// of a later session sees change where the surface differs from the one the map last observed
// there, which is not always the previous session's: when an object moved in a session whose
// fused keyframes never looked at its old place, the map still holds the object there, and a
// later keyframe looking at that place sees change the previous session's world cannot explain.
// Thread safety: const methods are thread safe; addSession is not.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <unordered_set>
#include <vector>

#include "strata/sim/ray_scene.h"

namespace strata::selection {

class MapHistory {
 public:
  /// `cell_m`: the grid on which "this session saw that place" is kept; coarser than the map's
  /// voxels so that a surface seen from a slightly different pixel still counts as seen.
  explicit MapHistory(float cell_m = 0.1f);

  /// Appends a finished session: its world and the true surface points (world frame) of the
  /// keyframes fused from it.
  void addSession(std::unique_ptr<sim::RayScene> scene,
                  const std::vector<Eigen::Vector3f>& fused_surface_W);

  int sessionCount() const { return static_cast<int>(sessions_.size()); }

  /// Per ray: the distance to the first surface in the world of the latest session whose fused
  /// keyframes saw that surface; negative where no session saw it (the map only knows it from
  /// nowhere: unmapped, not changed).
  std::vector<float> lastObservedDistance(const std::vector<sim::Ray>& rays) const;

 private:
  struct Session {
    std::unique_ptr<sim::RayScene> scene;
    std::unordered_set<std::uint64_t> seen_cells;
  };
  std::uint64_t cellKey(const Eigen::Vector3f& p_W) const;

  float cell_m_;
  std::vector<Session> sessions_;
};

}  // namespace strata::selection
