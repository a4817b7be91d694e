#include "strata/sim/world/world_scene.h"

#include <algorithm>
#include <thread>

#include "strata/core/parallel_for.h"
#include "strata/sim/world/session_truth.h"
#include "strata/sim/world/internal/world_scene_impl.h"

namespace strata::sim {
namespace {

constexpr int kPacket = 16;

/// Adds an instance of `scene` with pose T_W_O to `top` as geometry `id`.
void attachInstance(RTCDevice device, RTCScene top, RTCScene scene, const Eigen::Isometry3d& T_W_O,
                    unsigned id) {
  RtcGeometryPtr instance(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE));
  checkEmbree(device, "rtcNewGeometry(INSTANCE)");
  rtcSetGeometryInstancedScene(instance.get(), scene);
  const Eigen::Matrix<float, 3, 4> xfm = T_W_O.matrix().topRows<3>().cast<float>();  // col-major
  rtcSetGeometryTransform(instance.get(), 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
  rtcCommitGeometry(instance.get());
  checkEmbree(device, "rtcCommitGeometry(INSTANCE)");
  rtcAttachGeometryByID(top, instance.get(), id);
  checkEmbree(device, "rtcAttachGeometryByID(INSTANCE)");
}

void fillPacket(const Ray* rays, int count, RTCRayHit16& packet, int* valid) {
  for (int i = 0; i < kPacket; ++i) {
    const bool used = i < count && rays[i].origin_W.allFinite() && rays[i].direction_W.allFinite();
    valid[i] = used ? -1 : 0;
    const Ray& ray = rays[std::min(i, count - 1)];
    packet.ray.org_x[i] = ray.origin_W.x();
    packet.ray.org_y[i] = ray.origin_W.y();
    packet.ray.org_z[i] = ray.origin_W.z();
    packet.ray.dir_x[i] = ray.direction_W.x();
    packet.ray.dir_y[i] = ray.direction_W.y();
    packet.ray.dir_z[i] = ray.direction_W.z();
    packet.ray.tnear[i] = 0.0f;
    packet.ray.tfar[i] = ray.max_t_m;
    packet.ray.time[i] = 0.0f;
    packet.ray.mask[i] = 0xFFFFFFFFu;
    packet.ray.id[i] = static_cast<unsigned>(i);
    packet.ray.flags[i] = 0;
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
}

RayHit resolveHit(const WorldScene::Impl& impl, const RTCRayHit16& packet, int i,
                  const Eigen::Vector3f& direction_W) {
  RayHit hit;
  if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) return hit;
  const unsigned object_id = packet.hit.instID[0][i];
  const PartData& part = impl.assets->part(object_id, packet.hit.geomID[i]);
  // NOTE: normals from our own tables rather than Embree's Ng, whose frame under instancing is
  // easy to get wrong; the instance rotation is exact here.
  Eigen::Vector3f normal = impl.R_W_O[object_id] * part.face_normals[packet.hit.primID[i]];
  if (normal.dot(direction_W) > 0.0f) normal = -normal;
  hit.t_m = packet.ray.tfar[i];
  hit.normal_W = normal;
  hit.object_id = static_cast<std::int32_t>(object_id);
  hit.material = part.material;
  return hit;
}

void intersectRange(const WorldScene::Impl& impl, const Ray* rays, std::size_t count,
                    RayHit* hits) {
  // rtcIntersect16 reads the packet and the valid mask with aligned 64-byte loads: both must be
  // aligned to 64 bytes (a mask that happened to be aligned crashed under AddressSanitizer's
  // stack layout).
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacket];
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // camera rays: neighbours share paths
  for (std::size_t begin = 0; begin < count; begin += kPacket) {
    const int n = static_cast<int>(std::min<std::size_t>(kPacket, count - begin));
    fillPacket(rays + begin, n, packet, valid);
    rtcIntersect16(valid, impl.top.get(), &context, &packet);
    for (int i = 0; i < n; ++i) {
      hits[begin + i] =
          valid[i] ? resolveHit(impl, packet, i, rays[begin + i].direction_W) : RayHit{};
    }
  }
}

int threadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(2, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace

WorldScene::WorldScene(std::shared_ptr<const SceneAssets> assets, const SessionTruth& session,
                       const Config& config)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.assets = std::move(assets);
  impl.session = session.index;
  impl.threads = threadCount(config.threads);
  impl.chunk_rays = std::max(kPacket, config.chunk_rays / kPacket * kPacket);
  RTCDevice device = impl.assets->device.get();
  impl.top = newEmbreeScene(device);
  impl.T_W_O.assign(session.objects.size() + 1, Eigen::Isometry3d::Identity());
  attachInstance(device, impl.top.get(), impl.assets->static_scene.get(), impl.T_W_O[0], 0);
  for (const ObjectState& object : session.objects) {
    if (!object.present) continue;
    impl.T_W_O[object.id] = object.T_W_O;
    attachInstance(device, impl.top.get(), impl.assets->object_scenes[object.id - 1].get(),
                   object.T_W_O, static_cast<unsigned>(object.id));
  }
  for (const Eigen::Isometry3d& T : impl.T_W_O) impl.R_W_O.push_back(T.linear().cast<float>());
  rtcCommitScene(impl.top.get());
  checkEmbree(device, "rtcCommitScene(session)");
}

WorldScene::~WorldScene() = default;

int WorldScene::sessionIndex() const { return impl_->session; }

void WorldScene::intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const {
  hits.resize(rays.size());
  const std::size_t chunk = static_cast<std::size_t>(impl_->chunk_rays);
  const int threads = rays.size() <= chunk ? 1 : impl_->threads;  // small batches: no thread start
  parallelForChunks(rays.size(), threads, chunk, [&](std::size_t begin, std::size_t end) {
    intersectRange(*impl_, rays.data() + begin, end - begin, hits.data() + begin);
  });
}

}  // namespace strata::sim
