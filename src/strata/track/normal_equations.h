#pragma once
// The normal equations of frame-to-model point-to-plane ICP for one live level against a model
// raycast. Device: shaders/track/track_normal_equations.comp via NormalEquationsKernel; the
// reference (normalEquationsReference) computes every pixel's terms the same way, in float, and
// sums them in double.
//
// Per live pixel with a vertex p_C and normal n_C (camera frame C of the live frame), at the
// estimate T_W_C, with the model rendered from T_W_M (depth z_M and world normals):
//   p_M = T_M_W T_W_C p_C, projected into the model image, nearest pixel (u, v);
//   v_M = z_M(u, v) · ray(u, v),   n_M = R_M_W n_W(u, v);
//   gates: |p_M − v_M| ≤ max_distance_m,  n_M · (R_M_C n_C) ≥ cos(max_normal_angle);
//   r = n_M · (p_M − v_M),   J = [ R_M_Cᵀ n_M ,  p_C × (R_M_Cᵀ n_M) ]   (T_W_C ← T_W_C exp(ξ),
//   ξ = (translation, rotation));   Huber weight w = 1, or huber_m / |r| beyond huber_m.
// Sums: JᵀJ (w-weighted, 21 unique entries), Jᵀr (w-weighted), r² (unweighted), inlier count.
#include <array>
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/vk/vk.h"

namespace strata {

/// Sums over the inliers. JtJ: upper triangle, row by row ((0,0), (0,1) ... (0,5), (1,1) ...).
struct NormalEquations {
  std::array<double, 21> JtJ{};
  std::array<double, 6> Jtr{};
  double residual_sq = 0.0;
  std::uint32_t inliers = 0;
};

/// The association gates and the robust weight (from TrackConfig).
struct AssociationGates {
  float max_distance_m = 0.1f;
  float min_normal_cos = 0.866f;
  float huber_m = 0.01f;  // 0: no robust weight
};

/// The model the live frame is matched against: a raycast at T_W_M (host form, for the reference).
struct ModelView {
  CameraIntrinsics intrinsics;
  Eigen::Isometry3d T_W_M = Eigen::Isometry3d::Identity();
  const std::vector<float>* depth_m = nullptr;            // z, 0 = no surface
  const std::vector<Eigen::Vector3f>* normal_W = nullptr;  // zero where no normal
  const std::vector<std::uint8_t>* hit = nullptr;
};

/// A live level (host form): per-pixel camera-frame xyzw, w = 1 valid.
struct LiveView {
  int width_px = 0;
  int height_px = 0;
  const std::vector<Eigen::Vector4f>* vertex_C = nullptr;
  const std::vector<Eigen::Vector4f>* normal_C = nullptr;
};

NormalEquations normalEquationsReference(const LiveView& live, const ModelView& model,
                                         const Eigen::Isometry3d& T_W_C,
                                         const AssociationGates& gates);

/// Device normal equations: live levels and the model are uploaded once per frame, then run()
/// is called once per Gauss-Newton iteration (one dispatch, per-workgroup partial sums in float
/// reduced in shared memory, summed on the host in double). Not thread safe.
class NormalEquationsKernel {
 public:
  explicit NormalEquationsKernel(vk::Context& context);
  /// Uploads the live levels (vertex and normal maps, xyzw float each).
  void setLive(const std::vector<LiveView>& levels);
  /// The model: depth (float per pixel) and world normals (vec4, w = 1 on a hit) in device
  /// buffers, e.g. RaycastKernel's outputs; they must stay alive and unchanged while run() is used.
  void setModel(const vk::Buffer& depth_m, const vk::Buffer& normal_W,
                const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_M);
  /// The same from host images (uploaded into buffers of this kernel).
  void setModel(const ModelView& model);
  NormalEquations run(int level, const Eigen::Isometry3d& T_W_C, const AssociationGates& gates,
                      double* device_ms = nullptr);

 private:
  struct LevelBuffers {
    int width_px = 0;
    int height_px = 0;
    vk::Buffer vertex;
    vk::Buffer normal;
  };
  vk::Context& context_;
  vk::ComputePipeline pipeline_;
  vk::TimestampQueries timer_;
  vk::Buffer params_;
  vk::Buffer partials_;
  std::vector<LevelBuffers> levels_;
  vk::Buffer own_depth_;
  vk::Buffer own_normal_;
  const vk::Buffer* model_depth_ = nullptr;
  const vk::Buffer* model_normal_ = nullptr;
  CameraIntrinsics model_intrinsics_;
  Eigen::Isometry3d T_W_M_ = Eigen::Isometry3d::Identity();
};

}  // namespace strata
