#pragma once
// What a simulated session saw, as ground truth for evaluation: exact surface points per object id
// (0 = static structure), from the rendered frames' exact depth and object-id images, with the
// number of frames that saw each (a TSDF voxel with constant weights gains one per frame, and
// counts as observed from a minimum weight on).
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

#include "strata/core/types.h"
#include "strata/sim/sensors/rgbd_camera.h"

namespace strata::change {

/// Thread safety: none (one session's frames are added in order).
class VisibleSurface {
 public:
  /// Points are thinned to one per cube of `spacing_m` (the first seen stands for its cube);
  /// every `pixel_stride`-th pixel on both axes is looked at (2 at 2 cm cubes: at 5 m a 640x480
  /// view's sampled pixels are 1.9 cm apart, so a frame that sees a cube samples it).
  explicit VisibleSurface(float spacing_m = 0.02f, int pixel_stride = 2);

  /// Adds the pixels whose measured depth is valid (what the mapper received), placed at their
  /// exact depth seen from the true pose T_W_C. A cube gains one view per frame when the pixel
  /// its centre projects to has a measured depth on the cube's surface: what gives a voxel
  /// weight in fusion (on surfaces where depth drops out often, fewer views than hits).
  void addFrame(const sim::SimulatedFrame& frame, const CameraIntrinsics& intrinsics,
                const Eigen::Isometry3d& T_W_C);
  /// Adds one view of a point (tests, merging records).
  void addPoint(int object_id, const Eigen::Vector3f& p_W, int views = 1);

  /// Points of an object seen in at least `min_views` frames (empty when none).
  std::vector<Eigen::Vector3f> points(int object_id, int min_views = 1) const;
  /// Ids seen, ascending (0 = static structure).
  std::vector<int> objectIds() const;
  float spacing() const { return spacing_m_; }

 private:
  struct Cloud {
    std::unordered_map<std::uint64_t, std::size_t> cubes;  // cube -> index below
    std::vector<Eigen::Vector3f> points;
    std::vector<int> views;
    std::vector<std::uint64_t> last_frame;  // the frame that last counted a view
  };
  void addView(int object_id, const Eigen::Vector3f& p_W, int views, std::uint64_t frame);

  float spacing_m_;
  int pixel_stride_;
  std::uint64_t frames_ = 0;
  std::map<int, Cloud> clouds_;
};

}  // namespace strata::change
