#pragma once
// Depth endpoints as obstacles, for collision checks that must not lose thin structures.
//
// Why: a projective TSDF samples the scene at voxel centres. A shelf board 2.5 cm thick lies
// between the centres of 10 cm voxels, and rays passing beside it (seen edge-on, or under it to
// the back panel) write "free" into the voxels that hold it, so the ESDF can lose it entirely.
// The depth endpoints on the board stay: every endpoint is a point on a surface (up to noise).
//
// What: endpoints are binned in voxels of `voxel_size_m`; a voxel becomes an obstacle once
// endpoints fell in it from `min_views` camera positions at least `min_baseline_m` apart (places,
// not frames). Flying pixels (a depth between the two surfaces of an edge, along the edge pixel's
// ray) are what this must not keep: a robot turning in place sees the same edge along the same
// ray frame after frame and piles such points into the same voxels, while from another place the
// ray, and so the flying points, move and only real surfaces stay. Pixels behind a depth edge (a
// 4-neighbour more than `edge_jump_m` nearer: the far side, or a flying pixel between the sides)
// are not used at all; the near side is the edge's own surface and stays (a board seen edge-on
// is little more than its near-side pixels). A flying point passes only within edge_jump_m
// behind a near side, and must still be seen from min_views places. A surface seen at a grazing
// angle, whose depth changes fast from pixel to pixel, stays as long as the change is below
// edge_jump_m. Obstacles are never removed: for static worlds (exploration), not for scenes that
// change. An obstacle is the mean of the voxel's endpoints when it became one (on the surface up
// to the depth noise, where a voxel centre could lie half a diagonal off); a sphere is blocked
// when an obstacle lies within its radius.
// The defaults and the runs behind them: docs/explore.md, "Settings and why".
// Frames: world, metres. Thread safety: not thread safe.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/core/types.h"
#include "strata/map/block_index.h"  // BlockIndexHash: the map's key hash, for voxel and cell keys
#include "strata/plan/collision_checker.h"

namespace strata::explore {

struct SurfaceHitsConfig {
  float voxel_size_m = 0.05f;
  /// Camera positions that must have seen a voxel, each this far from the others (metres).
  int min_views = 3;
  float min_baseline_m = 0.2f;
  /// A pixel with a 4-neighbour nearer by more than this is behind an edge (metres). Default
  /// 0.3 m: above the pixel-to-pixel depth step of a grazing surface (a board's top from 0.2 m
  /// above at 2 m: ~0.28 m per pixel of a 160 px camera), so such surfaces are kept.
  float edge_jump_m = 0.3f;
  /// Side of the grid cells obstacles are looked up in (metres); about the check radius.
  float cell_size_m = 0.5f;
  /// Endpoints beyond this depth are not used (metres): far depth is noisier.
  float max_depth_m = 5.0f;
  /// Every stride-th pixel in u and v.
  int pixel_stride = 1;
};

class SurfaceHits {
 public:
  /// InputError for a non-positive size, min_views < 1 or > kMaxViews, a negative baseline or
  /// edge jump, or stride < 1.
  explicit SurfaceHits(const SurfaceHitsConfig& config = {});

  /// Adds the endpoints of one depth frame (z-depth, metres; 0 or non-finite: no depth) seen with
  /// `intrinsics` from `T_W_C`. InputError when the image size differs from the intrinsics.
  void addFrame(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                const Eigen::Isometry3d& T_W_C);
  /// Adds endpoints given in the world frame, seen from `camera_W`.
  void addPoints(const std::vector<Eigen::Vector3f>& points_W, const Eigen::Vector3f& camera_W);
  static constexpr int kMaxViews = 4;

  /// True when an obstacle lies within `radius_m` of `centre_W`.
  bool blocks(const Eigen::Vector3f& centre_W, float radius_m) const;
  std::size_t obstacleCount() const { return obstacle_count_; }

 private:
  struct VoxelHits {
    Eigen::Vector3f sum_W = Eigen::Vector3f::Zero();
    int points = 0;
    std::array<Eigen::Vector3f, kMaxViews> views_W;  // camera positions that counted
    int views = 0;
  };
  void addObstacle(const Eigen::Vector3f& p_W);

  SurfaceHitsConfig config_;
  std::unordered_map<Eigen::Vector3i, VoxelHits, BlockIndexHash> voxels_;
  /// Obstacle points per lookup cell.
  std::unordered_map<Eigen::Vector3i, std::vector<Eigen::Vector3f>, BlockIndexHash> cells_;
  std::size_t obstacle_count_ = 0;
};

/// A collision checker that also refuses spheres blocked by surface hits: the inner checker's
/// flags AND SurfaceHits::blocks. sample() is the inner checker's (the ESDF's distances and
/// gradients). Both must outlive it.
class HitGuardedChecker final : public plan::CollisionChecker {
 public:
  HitGuardedChecker(plan::CollisionChecker& inner, const SurfaceHits& hits)
      : inner_(&inner), hits_(&hits) {}
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                        float radius_m, UnknownPolicy unknown) override;
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override {
    return inner_->sample(points_W);
  }
  float voxelSize() const override { return inner_->voxelSize(); }
  float maxDistance() const override { return inner_->maxDistance(); }
  /// Spheres the ESDF passed and the hits refused.
  std::uint64_t refusedByHits() const { return refused_by_hits_; }

 private:
  plan::CollisionChecker* inner_;
  const SurfaceHits* hits_;
  std::uint64_t refused_by_hits_ = 0;
};

}  // namespace strata::explore
