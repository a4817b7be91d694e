// LiveView: camera poses, trajectories, camera info, and the objects of session ends.
#include <cmath>

#include "strata/camera_info_t.hpp"
#include "strata/core/error.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "view/live_decode.h"
#include "view/live_items.h"
#include "view/live_view.h"

namespace strata::view {
namespace {

/// A trajectory keeps a new point only this far from its last one (a still camera adds none).
constexpr float kMinStep_m = 0.001f;

Eigen::Isometry3d worldPose(const pose_t& message) {
  if (message.parent_frame != lcm_io::kWorldFrame) {
    throw InputError("pose in frame '" + message.parent_frame + "', expected '" +
                     lcm_io::kWorldFrame + "' (T_W_C)");
  }
  return lcm_io::decodePose(message);
}

/// The model-to-world transform of an object_update_t: the instance of the session that made the
/// update, else its last one.
Eigen::Isometry3d modelPlacement(const object_update_t& update) {
  if (update.instances.empty()) throw InputError("object_update_t: a model without instances");
  const object_instance_t* placed = &update.instances.back();
  for (const object_instance_t& instance : update.instances) {
    if (instance.session == update.session) placed = &instance;
  }
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = placed->T_W_M[4 * r + c];
  }
  if (!T.allFinite()) throw InputError("object_update_t: T_W_M is not finite");
  Eigen::Isometry3d T_W_M;
  T_W_M.matrix() = T;
  return T_W_M;
}

}  // namespace

void LiveView::onPose(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    pose_t message;
    lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
    applyPose(message.utime, worldPose(message), &vio_trajectory_);
  });
}

void LiveView::onFrame(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    const std::optional<pose_t> pose = framePose(buffer->data, static_cast<int>(buffer->data_size));
    if (pose) applyPose(pose->utime, worldPose(*pose), &map_trajectory_);
  });
}

void LiveView::onCameraInfo(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    camera_info_t m;
    lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), m);
    const std::array<double, 6> k{double(m.width), double(m.height), m.fx, m.fy, m.cx, m.cy};
    for (double v : k) {
      if (!std::isfinite(v)) throw InputError("camera_info_t: intrinsics not finite");
    }
    if (m.width <= 0 || m.height <= 0 || m.fx <= 0 || m.fy <= 0) {
      throw InputError("camera_info_t: size or focal length not positive");
    }
    intrinsics_ = k;
  });
}

void LiveView::applyPose(std::int64_t utime, const Eigen::Isometry3d& T_W_C,
                         Trajectory* trajectory) {
  scene_.put("pose", poseMessage("camera", T_W_C, static_cast<double>(utime) * 1e-6, intrinsics_,
                                 lcm_io::nowUtime()));
  const Eigen::Vector3f p = T_W_C.translation().cast<float>();
  auto& points = trajectory->points_W;
  if (points.empty() || (points.back() - p).norm() >= kMinStep_m) {
    points.push_back(p);
    trajectory->dirty = true;
  }
  if (points.size() > kMaxTrajectoryPoints) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < points.size(); i += 2) points[kept++] = points[i];
    if ((points.size() - 1) % 2 != 0) points[kept++] = p;  // the newest point stays
    points.resize(kept);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.poses;
}

void LiveView::onChange(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    const change_event_t e = decodeChangeEvent(buffer->data, static_cast<int>(buffer->data_size));
    const Mesh mesh = messageMesh(e.vertices, e.triangles, "change_event_t");
    const std::string id =
        "object:" + std::to_string(e.session) + ":" + std::to_string(e.object_id);
    if (objects_.count(id) == 0 && objects_.size() >= kMaxObjects) {
      throw InputError("more than " + std::to_string(kMaxObjects) + " objects; refused");
    }
    ObjectItem& item = objects_[id];
    item.mesh_id = id;
    item.box.id = e.object_id;
    item.box.session = e.session;
    item.box.label =
        "session " + std::to_string(e.session) + " object " + std::to_string(e.object_id);
    meshBounds(mesh, &item.box.min_W, &item.box.max_W);
    scene_.put(id, meshMessage(id, "object", mesh, e.session, item.box.label));
    putObjects();
  });
}

void LiveView::onObjects(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    const object_update_t u = decodeObjectUpdate(buffer->data, static_cast<int>(buffer->data_size));
    const Mesh mesh = messageMesh(u.vertices, u.triangles, "object_update_t", modelPlacement(u));
    const std::string id = "model:" + std::to_string(u.model_id);
    if (objects_.count(id) == 0 && objects_.size() >= kMaxObjects) {
      throw InputError("more than " + std::to_string(kMaxObjects) + " objects; refused");
    }
    // The model replaces the session segments it was made from.
    for (const object_instance_t& instance : u.instances) {
      const std::string segment =
          "object:" + std::to_string(instance.session) + ":" + std::to_string(instance.segment_id);
      if (objects_.erase(segment) > 0) scene_.remove(segment);
    }
    ObjectItem& item = objects_[id];
    item.mesh_id = id;
    item.box.id = u.model_id;
    item.box.session = u.session;
    item.box.label = "model " + std::to_string(u.model_id);
    meshBounds(mesh, &item.box.min_W, &item.box.max_W);
    scene_.put(id, meshMessage(id, "object", mesh, u.session, item.box.label));
    putObjects();
  });
}

void LiveView::putObjects() {
  std::vector<ObjectBox> boxes;
  boxes.reserve(objects_.size());
  for (const auto& [id, item] : objects_) boxes.push_back(item.box);
  scene_.put("objects", objectsMessage(boxes));
}

}  // namespace strata::view
