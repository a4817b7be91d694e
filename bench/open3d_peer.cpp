#include "open3d_peer.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "strata/core/clock.h"
#include "strata/mesh/mesh_metrics.h"
#include "open3d/Open3DConfig.h"
#include "open3d/core/Tensor.h"
#include "open3d/t/geometry/Image.h"
#include "open3d/t/geometry/TriangleMesh.h"
#include "open3d/t/geometry/VoxelBlockGrid.h"
#include "open3d/utility/Logging.h"
#include "open3d/utility/Parallel.h"
#include "summary.h"

namespace strata::bench {
namespace {

namespace o3c = open3d::core;
namespace o3g = open3d::t::geometry;
using Clock = std::chrono::steady_clock;

/// Depth handed to Open3D as uint16 millimetres with depth_scale 1000: the dataset's own PNG scale
/// (the raw format Open3D's integrate example feeds), so the depths equal ours exactly.
constexpr float kDepthScale = 1000.0f;
/// Voxels per block edge, as in Strata (8^3 voxels per block).
constexpr std::int64_t kBlockResolution = 8;
/// Open3D meshes voxels with weight > threshold; 0 keeps every observed voxel, as Strata's
/// MeshOptions::min_weight (1e-3) does. Open3D's default, 3, would drop surfaces seen < 4 times.
constexpr float kMeshWeightThreshold = 0.0f;
/// A never-observed block far from any scene (blocks of 8 voxels: 8.4e6 voxels out), activated
/// first so that it holds buffer slot 0. NOTE: Open3D 0.16's ExtractTriangleMesh asserts
/// `linear_idx_e > 0` (VoxelBlockGridImpl.h:1590, off by one: index 0 is valid), which aborts
/// the process whenever voxel (0,0,0) of slot 0 lies on a surface; with this block there, it never
/// does. Debian builds Open3D with assertions on.
constexpr int kPlaceholderBlock = 1 << 20;

o3c::Tensor placeholderKey() {
  return o3c::Tensor(std::vector<int>{kPlaceholderBlock, kPlaceholderBlock, kPlaceholderBlock},
                     {1, 3}, o3c::Int32);
}

/// Activates the placeholder block (slot 0 of a fresh grid) with all attributes zero: unobserved.
void reserveSlotZero(o3g::VoxelBlockGrid& grid) {
  auto [slots, masks] = grid.GetHashMap().Activate(placeholderKey());
  const std::int64_t slot = slots[0].Item<int>();
  for (const char* attribute : {"tsdf", "weight", "color"}) {
    grid.GetAttribute(attribute).Slice(0, slot, slot + 1).Fill(0.0f);
  }
}

/// True while the placeholder still holds slot 0 (a rehash, when the grid grows past its initial
/// capacity, may hand slots out anew).
bool slotZeroReserved(o3g::VoxelBlockGrid& grid) {
  auto [slots, masks] = grid.GetHashMap().Find(placeholderKey());
  return masks[0].Item<bool>() && slots[0].Item<int>() == 0;
}

o3c::Tensor matrixTensor(const Eigen::Matrix4d& m, int rows) {
  std::vector<double> values;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < rows; ++c) values.push_back(m(r, c));
  }
  return o3c::Tensor(values, {rows, rows}, o3c::Float64);
}

o3g::Image depthImage(const DepthImage& depth) {
  std::vector<std::uint16_t> mm(depth.depth_m.size());
  for (std::size_t i = 0; i < mm.size(); ++i) {
    const float d = depth.depth_m[i];
    mm[i] =
        std::isfinite(d) && d > 0.0f ? static_cast<std::uint16_t>(std::lround(d * kDepthScale)) : 0;
  }
  return o3g::Image(o3c::Tensor(mm, {depth.height_px, depth.width_px, 1}, o3c::UInt16));
}

o3g::Image colorImage(const ColorImage& color) {
  return o3g::Image(o3c::Tensor(color.rgb, {color.height_px, color.width_px, 3}, o3c::UInt8));
}

Mesh toStrataMesh(const o3g::TriangleMesh& mesh) {
  Mesh out;
  if (!mesh.HasVertexPositions()) return out;
  const o3c::Tensor positions = mesh.GetVertexPositions().To(o3c::Float32).Contiguous();
  const float* p = positions.GetDataPtr<float>();
  out.vertices.resize(static_cast<std::size_t>(positions.GetLength()));
  for (std::size_t i = 0; i < out.vertices.size(); ++i) {
    out.vertices[i] = Eigen::Vector3f(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  }
  if (!mesh.HasTriangleIndices()) return out;
  const o3c::Tensor triangles = mesh.GetTriangleIndices().To(o3c::Int32).Contiguous();
  const int* t = triangles.GetDataPtr<int>();
  out.triangles.resize(static_cast<std::size_t>(triangles.GetLength()));
  for (std::size_t i = 0; i < out.triangles.size(); ++i) {
    out.triangles[i] = Eigen::Vector3i(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
  }
  return out;
}

std::string peerName() {
  return "open3d::t::geometry::VoxelBlockGrid (CPU, Open3D " +
         std::to_string(OPEN3D_VERSION_MAJOR) + "." + std::to_string(OPEN3D_VERSION_MINOR) + "." +
         std::to_string(OPEN3D_VERSION_PATCH) + ")";
}

Json differences() {
  return Json::array()
      .push(
          "Open3D: distance along the optical axis (depth - z), weight 1 per observation, "
          "truncated pixel coordinates, voxel samples at integer multiples of the voxel size, no "
          "min depth; Strata defaults: point-to-plane distance, weight 1/z^2 with drop-off "
          "behind the surface, nearest pixel, voxel centres, min depth 0.1 m")
      .push(
          "Open3D map: float tsdf + float weight + 3 float colour = 20 B per voxel; both "
          "integrate colour")
      .push(
          "Open3D runs on the host CPU (OpenMP), Strata on the Vulkan device (here lavapipe on "
          "the same CPU)")
      .push(
          "Chamfer is vertex to nearest vertex: identical surfaces sampled on different grids "
          "still give a few tenths of a voxel; Open3D's marching cubes also meshes the +/- "
          "truncation seam behind thin objects, which Strata's rejects");
}

class Open3dPeerImpl final : public Open3dPeer {
 public:
  explicit Open3dPeerImpl(const PreloadedFrames& data) {
    open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Warning);
    const CameraIntrinsics& k = data.intrinsics;
    Eigen::Matrix4d intrinsic = Eigen::Matrix4d::Identity();
    intrinsic(0, 0) = k.fx_px;
    intrinsic(1, 1) = k.fy_px;
    intrinsic(0, 2) = k.cx_px;
    intrinsic(1, 2) = k.cy_px;
    intrinsic_ = matrixTensor(intrinsic, 3);
    for (const RgbdFrame& frame : data.frames) {
      depth_.push_back(depthImage(frame.depth));
      color_.push_back(colorImage(frame.color));
      T_C_W_.push_back(matrixTensor(frame.T_W_C.inverse().matrix(), 4));  // extrinsic
    }
  }

  Json describe() const override {
    return Json::object()
        .set("peer", peerName())
        .set("threads", open3d::utility::EstimateMaxThreads())
        .set("differences", differences());
  }

  Json run(const MapConfig& config, const DeviceRun& strata) override {
    o3g::VoxelBlockGrid grid(
        {"tsdf", "weight", "color"}, {o3c::Float32, o3c::Float32, o3c::Float32}, {{1}, {1}, {3}},
        config.voxel_size_m, kBlockResolution, config.initial_block_capacity, o3c::Device("CPU:0"));
    reserveSlotZero(grid);
    std::vector<double> frame_ms;
    for (std::size_t i = 0; i < depth_.size(); ++i) {
      // As Open3D's integrate example: frustum blocks, then integration into them.
      const auto start = Clock::now();
      const o3c::Tensor blocks =
          grid.GetUniqueBlockCoordinates(depth_[i], intrinsic_, T_C_W_[i], kDepthScale,
                                         config.max_depth_m, config.truncation_voxels);
      if (color_[i].IsEmpty()) {
        grid.Integrate(blocks, depth_[i], intrinsic_, T_C_W_[i], kDepthScale, config.max_depth_m,
                       config.truncation_voxels);
      } else {
        grid.Integrate(blocks, depth_[i], color_[i], intrinsic_, T_C_W_[i], kDepthScale,
                       config.max_depth_m, config.truncation_voxels);
      }
      frame_ms.push_back(msSince(start));
    }
    const std::int64_t blocks = grid.GetHashMap().Size() - 1;  // less the placeholder
    Mesh mesh;
    double mesh_ms = 0.0;
    const bool can_mesh = slotZeroReserved(grid);
    if (can_mesh) {
      const auto mesh_start = Clock::now();
      mesh = toStrataMesh(grid.ExtractTriangleMesh(kMeshWeightThreshold));
      mesh_ms = msSince(mesh_start);
    }
    std::fprintf(stderr, "  open3d: %zu frames, %ld blocks, mesh %zu vertices\n", depth_.size(),
                 static_cast<long>(blocks), mesh.vertices.size());
    Json out = report(config, strata, tail(frame_ms, kWarmupFrames), blocks, mesh_ms, mesh);
    if (!can_mesh) {
      out.set("mesh_skipped",
              "the grid grew and rehashed, so slot 0 may hold a scene block and "
              "Open3D 0.16's ExtractTriangleMesh could abort (see open3d_peer.cpp)");
    }
    return out;
  }

 private:
  static Json report(const MapConfig& config, const DeviceRun& strata,
                     const std::vector<double>& ms, std::int64_t blocks, double mesh_ms,
                     const Mesh& mesh) {
    const double device_ms = meanDeviceTotalMs(strata);
    const double wall_ms = meanWallMs(strata);
    Json chamfer;  // null when a mesh is empty
    if (!mesh.vertices.empty() && !strata.mesh.vertices.empty()) {
      const double metres = meshChamferDistance(strata.mesh, mesh);
      chamfer = Json::object().set("metres", metres).set("voxels", metres / config.voxel_size_m);
    }
    return Json::object()
        .set("peer", peerName())
        .set("frames_measured", ms.size())
        .set("ms_per_frame", meanMedian(ms))
        .set("open3d_over_strata_device_ms", device_ms > 0.0 ? mean(ms) / device_ms : 0.0)
        .set("open3d_over_strata_wall_ms", wall_ms > 0.0 ? mean(ms) / wall_ms : 0.0)
        .set("blocks_allocated", blocks)
        .set("mesh_weight_threshold", static_cast<double>(kMeshWeightThreshold))
        .set("mesh_extract_ms", mesh_ms)
        .set("mesh_vertices", mesh.vertices.size())
        .set("mesh_triangles", mesh.triangles.size())
        .set("chamfer_to_strata_mesh", chamfer);
  }

  o3c::Tensor intrinsic_;
  std::vector<o3g::Image> depth_;
  std::vector<o3g::Image> color_;
  std::vector<o3c::Tensor> T_C_W_;
};

}  // namespace

std::unique_ptr<Open3dPeer> makeOpen3dPeer(const PreloadedFrames& data) {
  return std::make_unique<Open3dPeerImpl>(data);
}

}  // namespace strata::bench
