#include "strata/sim/sensors/analytic_ray_scene.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "strata/core/error.h"
#include "strata/core/parallel_for.h"

namespace strata::sim {
namespace {

// Rays per parallel work item: small enough to balance, large enough to amortise the split.
constexpr int kRaysPerBlock = 4096;

template <typename Entries>
void closestHit(const Entries& entries, const Eigen::Vector3d& origin_W,
                const Eigen::Vector3d& dir_W, double* max_t_m, RayHit* best) {
  for (const auto& entry : entries) {
    const std::optional<SurfaceHit> hit = intersect(entry.primitive, origin_W, dir_W, *max_t_m);
    if (!hit) continue;
    *max_t_m = hit->t_m;
    best->t_m = static_cast<float>(hit->t_m);
    best->normal_W = hit->normal_W.cast<float>();  // outward = towards the outside origin
    best->object_id = entry.object_id;
    best->material = entry.material;
  }
}

template <typename Entries>
double minDistance(const Entries& entries, const Eigen::Vector3d& p_W, double distance) {
  for (const auto& entry : entries) {
    distance = std::min(distance, strata::sim::signedDistance(entry.primitive, p_W));
  }
  return distance;
}

void checkReflectivity(float reflectivity) {
  if (!(reflectivity >= 0.0f && reflectivity <= 1.0f)) {
    throw InputError("AnalyticRayScene: reflectivity must lie in [0, 1]");
  }
}

}  // namespace

template <typename Primitive>
std::int32_t AnalyticRayScene::addEntry(std::vector<Entry<Primitive>>& entries,
                                        const Primitive& primitive, std::int32_t object_id,
                                        float reflectivity) {
  checkReflectivity(reflectivity);
  ++primitive_count_;
  entries.push_back(
      Entry<Primitive>{primitive, object_id, Material{primitive.albedo, reflectivity}});
  return object_id;
}

std::int32_t AnalyticRayScene::add(Plane plane, float reflectivity) {
  const double norm = plane.normal_W.norm();
  if (!std::isfinite(norm) || norm < 1e-12 || !plane.point_W.allFinite()) {
    throw InputError("AnalyticRayScene: plane needs a finite point and a non-zero normal");
  }
  plane.normal_W /= norm;
  return addEntry(planes_, plane, kStaticObjectId, reflectivity);
}

std::int32_t AnalyticRayScene::add(const Box& box, float reflectivity) {
  const Eigen::Matrix3d& R = box.R_W_B;
  const bool rotation = R.allFinite() &&
                        (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
                        R.determinant() > 0.0;
  if (!box.centre_W.allFinite() || !(box.half_extents_m.minCoeff() > 0.0) || !rotation) {
    throw InputError(
        "AnalyticRayScene: box needs a finite centre, positive half extents and a "
        "rotation R_W_B");
  }
  return addEntry(boxes_, box, primitive_count_ + 1, reflectivity);
}

std::int32_t AnalyticRayScene::add(const Sphere& sphere, float reflectivity) {
  if (!sphere.centre_W.allFinite() || !(sphere.radius_m > 0.0) || !std::isfinite(sphere.radius_m)) {
    throw InputError("AnalyticRayScene: sphere needs a finite centre and a positive radius");
  }
  return addEntry(spheres_, sphere, primitive_count_ + 1, reflectivity);
}

RayHit AnalyticRayScene::castRay(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& unit_dir_W,
                                 double max_t_m) const {
  RayHit best;
  closestHit(planes_, origin_W, unit_dir_W, &max_t_m, &best);
  closestHit(boxes_, origin_W, unit_dir_W, &max_t_m, &best);
  closestHit(spheres_, origin_W, unit_dir_W, &max_t_m, &best);
  return best;
}

void AnalyticRayScene::intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const {
  hits.assign(rays.size(), RayHit{});
  const int blocks = static_cast<int>((rays.size() + kRaysPerBlock - 1) / kRaysPerBlock);
  parallelForBlocks(blocks, threads_, [&](int begin, int end) {
    const std::size_t last = std::min(rays.size(), static_cast<std::size_t>(end) * kRaysPerBlock);
    for (std::size_t i = static_cast<std::size_t>(begin) * kRaysPerBlock; i < last; ++i) {
      const Ray& ray = rays[i];
      hits[i] = castRay(ray.origin_W.cast<double>(), ray.direction_W.cast<double>().normalized(),
                        static_cast<double>(ray.max_t_m));
    }
  });
}

double AnalyticRayScene::signedDistance(const Eigen::Vector3d& p_W) const {
  double distance = std::numeric_limits<double>::infinity();
  distance = minDistance(planes_, p_W, distance);
  distance = minDistance(boxes_, p_W, distance);
  return minDistance(spheres_, p_W, distance);
}

float AnalyticRayScene::signedDistance(const Eigen::Vector3f& p_W) const {
  return static_cast<float>(signedDistance(Eigen::Vector3d(p_W.cast<double>())));
}

}  // namespace strata::sim
