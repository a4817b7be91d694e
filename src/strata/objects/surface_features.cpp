// SurfaceFeatures: a cloud's FPFH descriptors and search trees, prepared once for many
// registrations (object_registration.h).
#include <pcl/exceptions.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/objects/internal/surface_features_impl.h"

namespace strata::objects {
namespace {

void requireCloud(const SurfaceCloud& cloud, const std::string& name) {
  if (cloud.empty()) throw InputError("registerSurfaces: the " + name + " is empty");
  if (cloud.normals.size() != cloud.points.size()) {
    throw InputError("registerSurfaces: the " + name + " has " +
                     std::to_string(cloud.points.size()) + " points but " +
                     std::to_string(cloud.normals.size()) + " normals");
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float length = cloud.normals[i].norm();
    if (!cloud.points[i].allFinite() || !std::isfinite(length) || std::abs(length - 1.0f) > 0.1f) {
      throw InputError("registerSurfaces: the " + name + "'s point " + std::to_string(i) +
                       " has no unit normal (length " + std::to_string(length) +
                       ") or a non-finite position");
    }
  }
}

Cloud::Ptr toPcl(const SurfaceCloud& cloud) {
  Cloud::Ptr out(new Cloud);
  out->resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    pcl::PointNormal& p = (*out)[i];
    p.getVector3fMap() = cloud.points[i];
    p.getNormalVector3fMap() = cloud.normals[i];
    p.curvature = 0.0f;
  }
  return out;
}

Features::Ptr computeFpfh(const Cloud::Ptr& cloud,
                          const pcl::search::KdTree<pcl::PointNormal>::Ptr& tree, float radius_m) {
  pcl::FPFHEstimation<pcl::PointNormal, pcl::PointNormal, pcl::FPFHSignature33> estimation;
  estimation.setInputCloud(cloud);
  estimation.setInputNormals(cloud);
  estimation.setSearchMethod(tree);
  estimation.setRadiusSearch(radius_m);
  Features::Ptr features(new Features);
  estimation.compute(*features);
  return features;
}

bool finiteFeature(const pcl::FPFHSignature33& f) {
  return std::all_of(std::begin(f.histogram), std::end(f.histogram),
                     [](float v) { return std::isfinite(v); });
}

}  // namespace

SurfaceFeatures::SurfaceFeatures(const SurfaceCloud& cloud, const RegistrationConfig& config,
                                 const std::string& name) {
  config.validate();
  requireCloud(cloud, name);
  auto impl = std::make_shared<Impl>();
  impl->points = cloud.points;
  impl->radius_m = config.feature_radius_voxels * config.voxel_size_m;
  impl->finite_fpfh.reset(new Features);
  try {
    impl->cloud = toPcl(cloud);
    impl->point_tree = pcl::make_shared<pcl::search::KdTree<pcl::PointNormal>>();
    impl->point_tree->setInputCloud(impl->cloud);
    impl->fpfh = computeFpfh(impl->cloud, impl->point_tree, impl->radius_m);
    for (std::size_t i = 0; i < impl->fpfh->size(); ++i) {
      if (!finiteFeature((*impl->fpfh)[i])) continue;
      impl->finite_fpfh->push_back((*impl->fpfh)[i]);
      impl->finite_index.push_back(static_cast<int>(i));
    }
    if (!impl->finite_fpfh->empty()) impl->descriptor_tree.setInputCloud(impl->finite_fpfh);
  } catch (const pcl::PCLException& e) {
    impl->failure = e.what();
  }
  impl_ = std::move(impl);
}

std::size_t SurfaceFeatures::size() const { return impl_->points.size(); }

bool SurfaceFeatures::preparedFor(const RegistrationConfig& config) const {
  return impl_->radius_m == config.feature_radius_voxels * config.voxel_size_m;
}

}  // namespace strata::objects
