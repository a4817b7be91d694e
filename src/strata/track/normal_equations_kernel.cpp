#include <cstring>

#include "strata/core/error.h"
#include "strata/map/device_layout.h"
#include "strata/track/normal_equations.h"
#include "strata/vk/timed_dispatch.h"

namespace strata {
namespace {

/// std430 mirror of the Params block of track_normal_equations.comp.
struct TrackParams {
  float T_M_C[16];
  float R_M_W[16];
  float K_model[4];
  float gates[4];
};
static_assert(sizeof(TrackParams) == 160 && offsetof(TrackParams, K_model) == 128,
              "TrackParams layout");

// Pixels per workgroup: 128 invocations x kPixelsPerInvocation (track_normal_equations.comp).
constexpr std::uint32_t kPixelsPerGroup = 128 * 32;
constexpr std::size_t kPartialFloats = 32;

std::uint32_t groups(int width_px, int height_px) {
  const std::uint32_t pixels = static_cast<std::uint32_t>(width_px * height_px);
  return (pixels + kPixelsPerGroup - 1) / kPixelsPerGroup;
}

vk::Buffer uploadVec4(vk::Context& context, const std::vector<Eigen::Vector4f>& data,
                      const char* name) {
  vk::Buffer buffer = vk::Buffer::create(context, data.size() * 16, vk::MemoryUsage::kDeviceLocal,
                                         name);
  vk::upload(context, buffer, data.data(), data.size() * 16);
  return buffer;
}

}  // namespace

NormalEquationsKernel::NormalEquationsKernel(vk::Context& context)
    : context_(context),
      pipeline_(vk::ComputePipeline::create(context, "track_normal_equations", 6, 16)),
      timer_(vk::TimestampQueries::create(context, 2)),
      params_(vk::Buffer::create(context, sizeof(TrackParams), vk::MemoryUsage::kHostUpload,
                                 "track params")) {}

void NormalEquationsKernel::setLive(const std::vector<LiveView>& levels) {
  levels_.clear();
  std::size_t most_groups = 1;
  for (const LiveView& live : levels) {
    const std::size_t pixels = static_cast<std::size_t>(live.width_px) * live.height_px;
    if (pixels == 0 || live.vertex_C->size() != pixels || live.normal_C->size() != pixels) {
      throw InputError("track: a live level's maps do not match its size");
    }
    LevelBuffers buffers;
    buffers.width_px = live.width_px;
    buffers.height_px = live.height_px;
    buffers.vertex = uploadVec4(context_, *live.vertex_C, "track live vertices");
    buffers.normal = uploadVec4(context_, *live.normal_C, "track live normals");
    levels_.push_back(std::move(buffers));
    most_groups = std::max<std::size_t>(most_groups, groups(live.width_px, live.height_px));
  }
  const std::size_t bytes = most_groups * kPartialFloats * 4;
  if (!partials_.valid() || partials_.size() < bytes) {
    partials_ = vk::Buffer::create(context_, bytes, vk::MemoryUsage::kHostReadback,
                                   "track partial sums");
  }
}

void NormalEquationsKernel::setModel(const vk::Buffer& depth_m, const vk::Buffer& normal_W,
                                     const CameraIntrinsics& intrinsics,
                                     const Eigen::Isometry3d& T_W_M) {
  const std::size_t pixels = static_cast<std::size_t>(intrinsics.width_px) * intrinsics.height_px;
  if (depth_m.size() < pixels * 4 || normal_W.size() < pixels * 16) {
    throw InputError("track: the model buffers are smaller than the model image");
  }
  model_depth_ = &depth_m;
  model_normal_ = &normal_W;
  model_intrinsics_ = intrinsics;
  T_W_M_ = T_W_M;
}

void NormalEquationsKernel::setModel(const ModelView& model) {
  const std::size_t pixels =
      static_cast<std::size_t>(model.intrinsics.width_px) * model.intrinsics.height_px;
  std::vector<Eigen::Vector4f> normals(pixels, Eigen::Vector4f::Zero());
  for (std::size_t i = 0; i < pixels; ++i) {
    const Eigen::Vector3f& n = (*model.normal_W)[i];
    normals[i] = Eigen::Vector4f(n.x(), n.y(), n.z(), (*model.hit)[i] != 0 ? 1.0f : 0.0f);
  }
  own_depth_ = vk::Buffer::create(context_, pixels * 4, vk::MemoryUsage::kDeviceLocal,
                                  "track model depth");
  vk::upload(context_, own_depth_, model.depth_m->data(), pixels * 4);
  own_normal_ = uploadVec4(context_, normals, "track model normals");
  setModel(own_depth_, own_normal_, model.intrinsics, model.T_W_M);
}

NormalEquations NormalEquationsKernel::run(int level, const Eigen::Isometry3d& T_W_C,
                                           const AssociationGates& gates, double* device_ms) {
  if (level < 0 || level >= static_cast<int>(levels_.size())) {
    throw InputError("track: live level " + std::to_string(level) + " was not uploaded");
  }
  if (model_depth_ == nullptr) throw InputError("track: no model set");
  const LevelBuffers& live = levels_[static_cast<std::size_t>(level)];

  const Eigen::Isometry3d T_M_W = T_W_M_.inverse();
  TrackParams params{};
  gpu::storeMatrix((T_M_W * T_W_C).matrix().cast<float>(), params.T_M_C);
  Eigen::Matrix4f R_M_W = Eigen::Matrix4f::Identity();
  R_M_W.topLeftCorner<3, 3>() = T_M_W.rotation().cast<float>();
  gpu::storeMatrix(R_M_W, params.R_M_W);
  params.K_model[0] = model_intrinsics_.fx_px;
  params.K_model[1] = model_intrinsics_.fy_px;
  params.K_model[2] = model_intrinsics_.cx_px;
  params.K_model[3] = model_intrinsics_.cy_px;
  params.gates[0] = gates.max_distance_m * gates.max_distance_m;
  params.gates[1] = gates.min_normal_cos;
  params.gates[2] = gates.huber_m;
  std::memcpy(params_.mapped(), &params, sizeof(params));
  const std::uint32_t push[4] = {static_cast<std::uint32_t>(live.width_px),
                                 static_cast<std::uint32_t>(live.height_px),
                                 static_cast<std::uint32_t>(model_intrinsics_.width_px),
                                 static_cast<std::uint32_t>(model_intrinsics_.height_px)};

  vk::DescriptorSet set = vk::DescriptorSet::create(
      context_, pipeline_,
      {&live.vertex, &live.normal, model_depth_, model_normal_, &params_, &partials_});
  const std::uint32_t gx = groups(live.width_px, live.height_px);
  const double ms = dispatchTimed(context_, pipeline_, set, push, sizeof(push), gx, 1, timer_);
  if (device_ms != nullptr) *device_ms = ms;

  NormalEquations sums;
  const auto* partial = static_cast<const float*>(partials_.mapped());
  double count = 0.0;
  for (std::size_t g = 0; g < gx; ++g) {
    const float* p = partial + g * kPartialFloats;
    for (int k = 0; k < 21; ++k) sums.JtJ[static_cast<std::size_t>(k)] += p[k];
    for (int k = 0; k < 6; ++k) sums.Jtr[static_cast<std::size_t>(k)] += p[21 + k];
    sums.residual_sq += p[27];
    count += p[28];
  }
  sums.inliers = static_cast<std::uint32_t>(count + 0.5);
  return sums;
}

}  // namespace strata
