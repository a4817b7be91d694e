#include <chrono>
#include <cmath>
#include <cstring>

#include "open3d/Open3DConfig.h"
#include "open3d/camera/PinholeCameraIntrinsic.h"
#include "open3d/geometry/Image.h"
#include "open3d/geometry/RGBDImage.h"
#include "open3d/pipelines/odometry/Odometry.h"
#include "open3d/utility/Logging.h"
#include "open3d/utility/Parallel.h"
#include "track_peer.h"

#include "strata/core/clock.h"

namespace strata::bench {
namespace {

/// Open3D's odometry default depth range is [0, 4] m; the RGBD images are truncated there too.
constexpr double kDepthTrunc_m = 4.0;

std::shared_ptr<open3d::geometry::RGBDImage> toOpen3d(const RgbdFrame& frame) {
  open3d::geometry::Image color;
  color.Prepare(frame.color.width_px, frame.color.height_px, 3, 1);
  std::memcpy(color.data_.data(), frame.color.rgb.data(), frame.color.rgb.size());
  open3d::geometry::Image depth;
  depth.Prepare(frame.depth.width_px, frame.depth.height_px, 1, 2);
  auto* mm = reinterpret_cast<std::uint16_t*>(depth.data_.data());
  for (std::size_t i = 0; i < frame.depth.depth_m.size(); ++i) {
    const float d = frame.depth.depth_m[i];
    mm[i] = std::isfinite(d) && d > 0.0f ? static_cast<std::uint16_t>(std::lround(d * 1000.0f))
                                         : 0;
  }
  return open3d::geometry::RGBDImage::CreateFromColorAndDepth(color, depth, 1000.0, kDepthTrunc_m,
                                                              true);
}

}  // namespace

PeerTrajectory runPeerOdometry(const PreloadedFrames& data) {
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  PeerTrajectory out;
  out.available = true;
  out.peer = std::string("Open3D ") + OPEN3D_VERSION;
  out.method =
      "pipelines::odometry::ComputeRGBDOdometry, frame to frame, hybrid Jacobian (depth + "
      "intensity), default OdometryOption (pyramid iterations 20/10/5, depth_diff_max 3 cm, "
      "depth [0, 4] m), initial guess identity; images converted before timing";
  out.threads = open3d::utility::EstimateMaxThreads();
  const auto& f = data.frames;
  const CameraIntrinsics& in = data.intrinsics;
  const open3d::camera::PinholeCameraIntrinsic intrinsic(in.width_px, in.height_px, in.fx_px,
                                                         in.fy_px, in.cx_px, in.cy_px);
  std::vector<std::shared_ptr<open3d::geometry::RGBDImage>> images;
  for (const RgbdFrame& frame : f) images.push_back(toOpen3d(frame));
  out.T_W_C.push_back(f.front().T_W_C);
  for (std::size_t i = 1; i < f.size(); ++i) {
    const auto start = std::chrono::steady_clock::now();
    // NOTE: source = the new frame, target = the previous: the result maps new-camera points
    // into the previous camera (T_prev_new), as Open3D's reconstruction system chains it.
    const auto [success, T_prev_new, information] =
        open3d::pipelines::odometry::ComputeRGBDOdometry(*images[i], *images[i - 1], intrinsic);
    out.ms.push_back(msSince(start));
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    if (success) {
      step.matrix() = T_prev_new;
    } else {
      ++out.failures;
    }
    out.T_W_C.push_back(out.T_W_C.back() * step);
  }
  return out;
}

}  // namespace strata::bench
