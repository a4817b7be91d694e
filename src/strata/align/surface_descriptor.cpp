// Keyframe surface descriptors: depth -> downsampled cloud -> normals -> FPFH at non-planar
// points -> global descriptor.
#include "strata/align/surface_descriptor.h"

#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "strata/core/error.h"

namespace strata::align {
namespace {

constexpr int kMinCloudPoints = 50;
constexpr int kDistanceBins = 16;
constexpr float kMaxDistance_m = 8.0f;  // D2 and range histograms cover [0, 8) m
constexpr std::size_t kDistancePairs = 4000;

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr sampledCloud(const DepthImage& depth, const CameraIntrinsics& k,
                        const SurfaceConfig& config) {
  Cloud::Ptr raw(new Cloud);
  for (int v = 0; v < depth.height_px; v += config.stride_px) {
    for (int u = 0; u < depth.width_px; u += config.stride_px) {
      const float z = depth.at(u, v);
      if (!(z >= config.min_depth_m && z <= config.max_depth_m)) continue;  // NaN fails too
      raw->push_back({(u - k.cx_px) / k.fx_px * z, (v - k.cy_px) / k.fy_px * z, z});
    }
  }
  Cloud::Ptr out(new Cloud);
  if (raw->size() < static_cast<std::size_t>(kMinCloudPoints)) return out;
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(raw);
  grid.setLeafSize(config.voxel_m, config.voxel_m, config.voxel_m);
  grid.filter(*out);
  return out;
}

void addNormalised(std::vector<float>& out, const std::vector<double>& histogram) {
  double sum = 0.0;
  for (double h : histogram) sum += h;
  for (double h : histogram) out.push_back(sum > 0.0 ? static_cast<float>(h / sum) : 0.0f);
}

int distanceBin(float d_m) {
  return std::clamp(static_cast<int>(d_m / kMaxDistance_m * kDistanceBins), 0, kDistanceBins - 1);
}

// Mean keypoint FPFH, D2 over deterministic point pairs, ranges.
std::vector<float> globalDescriptor(const Cloud& cloud, const std::vector<Fpfh>& fpfh) {
  std::vector<double> mean(33, 0.0), d2(kDistanceBins, 0.0), range(kDistanceBins, 0.0);
  for (const Fpfh& f : fpfh)
    for (std::size_t i = 0; i < f.size(); ++i) mean[i] += f[i];
  const std::size_t n = cloud.size();
  for (std::size_t i = 0; i < kDistancePairs; ++i) {
    // A fixed walk over pairs (Knuth's multiplicative hash): the same cloud, the same histogram.
    const std::size_t p = (i * 2654435761u) % n, q = (i * 40503u + n / 2 + 1) % n;
    if (p == q) continue;
    d2[distanceBin((cloud[p].getVector3fMap() - cloud[q].getVector3fMap()).norm())] += 1.0;
  }
  for (const pcl::PointXYZ& p : cloud) range[distanceBin(p.getVector3fMap().norm())] += 1.0;
  std::vector<float> out;
  addNormalised(out, mean);
  addNormalised(out, d2);
  addNormalised(out, range);
  return out;
}

}  // namespace

void SurfaceConfig::validate() const {
  if (stride_px < 1) throw InputError("SurfaceConfig: stride_px must be >= 1");
  if (!(voxel_m > 0.0f)) throw InputError("SurfaceConfig: voxel_m must be > 0");
  if (!(min_depth_m >= 0.0f && max_depth_m > min_depth_m)) {
    throw InputError("SurfaceConfig: need 0 <= min_depth_m < max_depth_m");
  }
  if (!(normal_radius_m > voxel_m)) {
    throw InputError("SurfaceConfig: normal_radius_m must exceed voxel_m");
  }
  if (!(fpfh_radius_m > normal_radius_m)) {
    throw InputError("SurfaceConfig: fpfh_radius_m must exceed normal_radius_m");
  }
  if (!(min_keypoint_variation >= 0.0f && min_keypoint_variation < 1.0f / 3.0f)) {
    throw InputError("SurfaceConfig: min_keypoint_variation must be in [0, 1/3)");
  }
  if (max_keypoints < 3) throw InputError("SurfaceConfig: max_keypoints must be >= 3");
}

KeyframeSurface describeSurface(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                                const SurfaceConfig& config) {
  config.validate();
  intrinsics.validate();
  if (depth.width_px != intrinsics.width_px || depth.height_px != intrinsics.height_px ||
      depth.depth_m.size() != static_cast<std::size_t>(depth.width_px) * depth.height_px) {
    throw InputError("describeSurface: depth image " + std::to_string(depth.width_px) + "x" +
                     std::to_string(depth.height_px) + " does not match the intrinsics " +
                     std::to_string(intrinsics.width_px) + "x" +
                     std::to_string(intrinsics.height_px));
  }
  KeyframeSurface out;
  const Cloud::Ptr cloud = sampledCloud(depth, intrinsics, config);
  if (cloud->size() < static_cast<std::size_t>(kMinCloudPoints)) return out;

  auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  tree->setInputCloud(cloud);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimate_normals;
  estimate_normals.setInputCloud(cloud);
  estimate_normals.setSearchMethod(tree);
  estimate_normals.setRadiusSearch(config.normal_radius_m);
  estimate_normals.setViewPoint(0.0f, 0.0f, 0.0f);  // normals face the camera
  estimate_normals.compute(*normals);

  // Keypoints: finite, non-planar, an even stride through them.
  std::vector<int> candidates;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const pcl::Normal& n = (*normals)[i];
    if (std::isfinite(n.normal_x) && std::isfinite(n.curvature) &&
        n.curvature >= config.min_keypoint_variation) {
      candidates.push_back(static_cast<int>(i));
    }
  }
  const std::size_t limit = static_cast<std::size_t>(config.max_keypoints);
  pcl::IndicesPtr keypoints(new pcl::Indices);
  for (std::size_t i = 0; i < std::min(limit, candidates.size()); ++i)
    keypoints->push_back(candidates[i * candidates.size() / std::min(limit, candidates.size())]);

  std::vector<Fpfh> fpfh;
  if (!keypoints->empty()) {
    pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> estimate_fpfh;
    estimate_fpfh.setInputCloud(cloud);
    estimate_fpfh.setInputNormals(normals);
    estimate_fpfh.setIndices(keypoints);
    estimate_fpfh.setSearchMethod(tree);
    estimate_fpfh.setRadiusSearch(config.fpfh_radius_m);
    pcl::PointCloud<pcl::FPFHSignature33> signatures;
    estimate_fpfh.compute(signatures);
    for (std::size_t i = 0; i < signatures.size(); ++i) {
      const float* h = signatures[i].histogram;
      if (!std::all_of(h, h + 33, [](float x) { return std::isfinite(x); })) continue;
      Fpfh f;
      std::copy(h, h + 33, f.begin());
      fpfh.push_back(f);
      out.keypoints_C_m.push_back((*cloud)[static_cast<std::size_t>((*keypoints)[i])]
                                      .getVector3fMap());
    }
  }
  out.global = globalDescriptor(*cloud, fpfh);
  out.fpfh = std::move(fpfh);
  return out;
}

double surfaceDistance(const KeyframeSurface& a, const KeyframeSurface& b) {
  if (a.global.empty() || a.global.size() != b.global.size())
    return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (std::size_t i = 0; i < a.global.size(); ++i) sum += std::abs(a.global[i] - b.global[i]);
  return sum;
}

}  // namespace strata::align
