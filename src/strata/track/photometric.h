#pragma once
// The photometric term of RGB-D tracking (host): the live frame's intensity against the model's
// as the raycast renders it (the voxels' colours), in the normal equations of the ICP's pose
// increment, so texture constrains what the geometry leaves loose (a rotation that the depth
// cannot tell from a sideways step).
//
// Per live pixel of a level with a vertex p_C, at the estimate T_W_C, with the model rendered
// from T_W_M at its own intrinsics:
//   p_M = T_M_W T_W_C p_C, projected to (u, v) in the model image (sub-pixel);
//   gates: the live pixel has a normal (not at a depth edge); the four model pixels around (u, v)
//          rendered a surface without a depth edge between them (depths within 2 %);
//          |z_M(u, v) - p_M.z| <= max_distance_m (the same surface, not one in front of it);
//          |grad I_M| >= min_gradient;
//   r = I_M(u, v) - I_L(p) (bilinear; intensities in [0, 1]);
//   J = [ b, p_C x b ],  b = R_M_C^T (grad I_M . dpi/dp)^T   (T_W_C <- T_W_C exp(xi), as the ICP);
//   Huber weight on r. Sums as NormalEquations (normal_equations.h).
// Thread safety: free functions without shared state.
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/raycast/raycast.h"
#include "strata/track/live_pyramid.h"
#include "strata/track/normal_equations.h"

namespace strata {

/// Intensity in [0, 1] (the mean of R, G and B over 255), row-major.
struct IntensityImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<float> value;
};

IntensityImage intensityOf(const ColorImage& color);
/// Half resolution (each pixel the mean of its 2x2 block), beside the depth pyramid's levels.
IntensityImage halfIntensity(const IntensityImage& image);

/// The model's intensity as rendered from T_W_M, with its gradient (central differences, 0
/// where a neighbour rendered no surface) and depth.
struct IntensityModel {
  CameraIntrinsics intrinsics;
  Eigen::Isometry3d T_W_M = Eigen::Isometry3d::Identity();
  IntensityImage intensity;
  std::vector<float> grad_u, grad_v;  // per pixel, intensity per pixel
  std::vector<float> depth_m;         // rendered z, 0 where no surface
};

IntensityModel intensityModel(const RaycastImage& raycast, const CameraIntrinsics& intrinsics,
                              const Eigen::Isometry3d& T_W_M);

struct PhotometricGates {
  float max_distance_m = 0.1f;
  float min_gradient = 0.005f;  // per pixel: below it a pixel constrains nothing
  float huber = 0.05f;          // on the intensity residual (0: none)
};

/// The photometric sums of live level `live` (its vertices; `intensity` of the same size).
NormalEquations photometricEquations(const LiveLevel& live, const IntensityImage& intensity,
                                     const IntensityModel& model, const Eigen::Isometry3d& T_W_C,
                                     const PhotometricGates& gates);

/// a + weight^2 b (JtJ, Jtr and r^2; the inliers stay a's: the ICP's).
NormalEquations addWeighted(const NormalEquations& a, const NormalEquations& b, double weight);

}  // namespace strata
