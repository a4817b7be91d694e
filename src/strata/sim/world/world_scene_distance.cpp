// WorldScene's ground-truth queries: inside/outside by counting ray crossings per closed part, and
// the exact distance to the nearest triangle by an Embree point query.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "strata/sim/world/triangle_distance.h"
#include "strata/sim/world/internal/world_scene_impl.h"

namespace strata::sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// Irregular directions: no axis plane, diagonal or simple ratio, so rays from the usual test
/// points (box centres, grid points) do not run exactly through edges or vertices of boxes.
const std::array<Eigen::Vector3f, 3>& voteDirections() {
  static const std::array<Eigen::Vector3f, 3> directions = {
      Eigen::Vector3f(0.3129f, 0.5431f, 0.7801f).normalized(),
      Eigen::Vector3f(-0.6712f, 0.2398f, -0.7014f).normalized(),
      Eigen::Vector3f(0.4418f, -0.8017f, -0.4027f).normalized()};
  return directions;
}

struct Crossing {
  unsigned object_id, geometry_id, primitive_id;
  bool operator<(const Crossing& o) const {
    return std::tie(object_id, geometry_id, primitive_id) <
           std::tie(o.object_id, o.geometry_id, o.primitive_id);
  }
  bool operator==(const Crossing& o) const {
    return object_id == o.object_id && geometry_id == o.geometry_id &&
           primitive_id == o.primitive_id;
  }
};

/// The context Embree hands back to the filter (it must start with RTCIntersectContext).
struct CrossingContext {
  RTCIntersectContext context;
  std::vector<Crossing> crossings;
  float nearest_m = kInf;
};

/// Records every hit and rejects it, so the traversal goes on to the next surface.
void recordCrossing(const RTCFilterFunctionNArguments* args) {
  auto* state = reinterpret_cast<CrossingContext*>(const_cast<RTCIntersectContext*>(args->context));
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    state->crossings.push_back({RTCHitN_instID(args->hit, args->N, i, 0),
                                RTCHitN_geomID(args->hit, args->N, i),
                                RTCHitN_primID(args->hit, args->N, i)});
    state->nearest_m = std::min(state->nearest_m, RTCRayN_tfar(args->ray, args->N, i));
    args->valid[i] = 0;
  }
}

/// True when some part is crossed an odd number of times. Duplicate reports of one triangle
/// (Embree may repeat a hit) count once.
bool oddPart(std::vector<Crossing>& crossings) {
  std::sort(crossings.begin(), crossings.end());
  crossings.erase(std::unique(crossings.begin(), crossings.end()), crossings.end());
  for (std::size_t i = 0; i < crossings.size();) {
    std::size_t j = i;
    while (j < crossings.size() && crossings[j].object_id == crossings[i].object_id &&
           crossings[j].geometry_id == crossings[i].geometry_id) {
      ++j;
    }
    if ((j - i) % 2 == 1) return true;
    i = j;
  }
  return false;
}

struct ClosestQuery {
  const WorldScene::Impl* impl;
  Eigen::Vector3d p_W;
  double best_squared;
};

/// Point-query callback: distance to one triangle, in world coordinates and double precision.
bool visitTriangle(RTCPointQueryFunctionArguments* args) {
  auto* query = static_cast<ClosestQuery*>(args->userPtr);
  const unsigned object_id = args->context->instStackSize > 0 ? args->context->instID[0] : 0;
  const PartData& part = query->impl->assets->part(object_id, args->geomID);
  const Eigen::Vector3i& t = part.mesh.triangles[args->primID];
  const Eigen::Isometry3d& T_W_O = query->impl->T_W_O[object_id];
  const Eigen::Vector3d a = T_W_O * part.mesh.vertices[t[0]].cast<double>();
  const Eigen::Vector3d b = T_W_O * part.mesh.vertices[t[1]].cast<double>();
  const Eigen::Vector3d c = T_W_O * part.mesh.vertices[t[2]].cast<double>();
  const double d2 = (closestPointOnTriangle(query->p_W, a, b, c) - query->p_W).squaredNorm();
  if (d2 >= query->best_squared) return false;
  query->best_squared = d2;
  // Shrink the search (world space; our transforms are rigid), rounded up so that float rounding
  // never culls a triangle at the same distance.
  args->query->radius = std::nextafter(static_cast<float>(std::sqrt(d2)), kInf);
  return true;
}

}  // namespace

bool WorldScene::Impl::inside(const Eigen::Vector3f& p_W, float* nearest_hit_m) const {
  int votes = 0;
  float nearest = kInf;
  for (const Eigen::Vector3f& direction : voteDirections()) {
    CrossingContext state;
    rtcInitIntersectContext(&state.context);
    state.context.filter = recordCrossing;
    RTCRayHit ray{};
    ray.ray.org_x = p_W.x(), ray.ray.org_y = p_W.y(), ray.ray.org_z = p_W.z();
    ray.ray.dir_x = direction.x(), ray.ray.dir_y = direction.y(), ray.ray.dir_z = direction.z();
    ray.ray.tnear = 0.0f;
    ray.ray.tfar = kInf;
    ray.ray.mask = 0xFFFFFFFFu;
    ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    ray.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top.get(), &state.context, &ray);
    nearest = std::min(nearest, state.nearest_m);
    if (oddPart(state.crossings)) ++votes;
  }
  if (nearest_hit_m != nullptr) *nearest_hit_m = nearest;
  return votes >= 2;
}

double WorldScene::Impl::nearestDistance(const Eigen::Vector3d& p_W, float radius_m) const {
  ClosestQuery closest{this, p_W, std::numeric_limits<double>::infinity()};
  alignas(16) RTCPointQuery query;
  query.x = static_cast<float>(p_W.x());
  query.y = static_cast<float>(p_W.y());
  query.z = static_cast<float>(p_W.z());
  query.radius = radius_m;
  query.time = 0.0f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(top.get(), &query, &context, visitTriangle, &closest);
  return std::sqrt(closest.best_squared);
}

float WorldScene::signedDistance(const Eigen::Vector3f& p_W) const {
  float nearest_hit = kInf;
  const bool in = impl_->inside(p_W, &nearest_hit);
  // A crossing at distance t bounds the nearest surface: search only within it (plus rounding).
  const float radius = std::isfinite(nearest_hit) ? nearest_hit * 1.0001f + 1e-4f : kInf;
  const double d = impl_->nearestDistance(p_W.cast<double>(), radius);
  return static_cast<float>(in ? -d : d);
}

bool WorldScene::occupied(const Eigen::Vector3f& p_W) const { return impl_->inside(p_W, nullptr); }

double WorldScene::distanceToSurface(const Eigen::Vector3d& p_W) const {
  return impl_->nearestDistance(p_W, kInf);
}

}  // namespace strata::sim
