#pragma once
// What SurfaceFeatures holds (internal: PCL types; included by the registration .cpp files only).
#include <pcl/features/fpfh.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "strata/objects/object_registration.h"

namespace strata::objects {

using Cloud = pcl::PointCloud<pcl::PointNormal>;
using Features = pcl::PointCloud<pcl::FPFHSignature33>;

struct SurfaceFeatures::Impl {
  std::vector<Eigen::Vector3f> points;  // the cloud's, for RANSAC
  Cloud::Ptr cloud;                     // points with normals
  Features::Ptr fpfh;                   // one per point (non-finite where PCL found too few)
  float radius_m = 0.0f;                // of the FPFH support
  /// The finite descriptors, a k-d tree over them, and each one's point index.
  Features::Ptr finite_fpfh;
  std::vector<int> finite_index;
  pcl::KdTreeFLANN<pcl::FPFHSignature33> descriptor_tree;
  /// A k-d tree over the points (nearest points in scoring and in ICP's correspondences).
  pcl::search::KdTree<pcl::PointNormal>::Ptr point_tree;
  /// PCL's exception text when preparing failed ("" otherwise): registerSurfaces then reports
  /// the registration as not converged with it, as for any unlucky data.
  std::string failure;
};

}  // namespace strata::objects
