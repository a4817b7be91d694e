#include "strata/change/change_detector.h"

#include <cmath>
#include <string>

#include "strata/change/internal/change_backend.h"
#include "strata/core/error.h"

namespace strata::change {

ChangeDetector::ChangeDetector(vk::Context& context, const MapConfig& map_config,
                               const ChangeConfig& config)
    : map_config_(map_config), config_(config) {
  map_config_.validate();
  config_.validate(map_config_.voxel_size_m);
  backend_ = makeDeviceBackend(context, map_config_, config_);
}

ChangeDetector::ChangeDetector(const MapConfig& map_config, const ChangeConfig& config)
    : map_config_(map_config), config_(config), reference_(true) {
  map_config_.validate();
  config_.validate(map_config_.voxel_size_m);
  backend_ = makeReferenceBackend(map_config_, config_);
}

ChangeDetector::~ChangeDetector() = default;
ChangeDetector::ChangeDetector(ChangeDetector&&) noexcept = default;
ChangeDetector& ChangeDetector::operator=(ChangeDetector&&) noexcept = default;

void ChangeDetector::requireSession(int session, const char* what) const {
  if (session < 0 || session >= sessionCount()) {
    throw InputError(std::string(what) + ": session " + std::to_string(session) +
                     " does not exist (" + std::to_string(sessionCount()) + " begun)");
  }
}

void ChangeDetector::requireLayers(int session, const char* what) const {
  requireSession(session, what);
  if (sessions_[session].released) {
    throw InputError(std::string(what) + ": session " + std::to_string(session) +
                     " was released (its layers now hold a later session)");
  }
}

int ChangeDetector::sessionLayer(int session) const {
  requireLayers(session, "sessionLayer");
  return backend_->sessionTsdfLayer(session);
}

void ChangeDetector::releaseSession(int session) {
  requireLayers(session, "releaseSession");
  if (!sessions_[session].ended) {
    throw InputError("releaseSession: session " + std::to_string(session) + " has not ended");
  }
  backend_->releaseSession(session);
  sessions_[session].released = true;
}

int ChangeDetector::beginSession() {
  const int session = sessionCount();
  backend_->addSession(session);
  sessions_.emplace_back();
  return session;
}

FrameStats ChangeDetector::integrate(int session, const RgbdFrame& frame,
                                     const CameraIntrinsics& intrinsics) {
  requireSession(session, "integrate");
  if (sessions_[session].ended) {
    throw InputError("integrate: session " + std::to_string(session) +
                     " has ended (it is merged into the static map)");
  }
  return backend_->integrate(session, frame, intrinsics);
}

void ChangeDetector::requireSameGrid(const TsdfMap& session_map, const char* what) const {
  const MapConfig& c = session_map.config();
  // The same voxel grid and band, or the layers would not compare voxel for voxel.
  if (std::fabs(c.voxel_size_m - map_config_.voxel_size_m) > 1e-7f ||
      std::fabs(c.truncationDistance() - map_config_.truncationDistance()) > 1e-7f) {
    throw InputError(std::string(what) + ": the map has voxel size " +
                     std::to_string(c.voxel_size_m) + " m and truncation " +
                     std::to_string(c.truncationDistance()) + " m; the detector uses " +
                     std::to_string(map_config_.voxel_size_m) + " m and " +
                     std::to_string(map_config_.truncationDistance()) + " m");
  }
}

void ChangeDetector::restore(const TsdfMap& static_map, int ended_sessions) {
  if (!sessions_.empty()) {
    throw InputError("restore: the detector has sessions already (" +
                     std::to_string(sessions_.size()) + ")");
  }
  if (ended_sessions < 0) throw InputError("restore: a negative count of ended sessions");
  requireSameGrid(static_map, "restore");
  backend_->restore(static_map, ended_sessions);
  Session ended;
  ended.ended = true;
  ended.released = true;
  sessions_.assign(static_cast<std::size_t>(ended_sessions), ended);
  ended_ = ended_sessions;
}

int ChangeDetector::addSessionMap(const TsdfMap& session_map) {
  requireSameGrid(session_map, "addSessionMap");
  const int session = beginSession();
  backend_->setSessionMap(session, session_map);
  return session;
}

void ChangeDetector::replaceSessionMap(int session, const TsdfMap& session_map) {
  requireSession(session, "replaceSessionMap");
  if (sessions_[session].ended) {
    throw InputError("replaceSessionMap: session " + std::to_string(session) +
                     " has ended (it is merged into the static map)");
  }
  requireSameGrid(session_map, "replaceSessionMap");
  backend_->setSessionMap(session, session_map);
}

ChangeUpdateStats ChangeDetector::endSession(int session) {
  requireSession(session, "endSession");
  if (session != ended_) {
    throw InputError("endSession: sessions end in the order they began; the next is " +
                     std::to_string(ended_) + ", not " + std::to_string(session));
  }
  ChangeUpdateStats stats = backend_->update(session);
  stats.session = session;
  sessions_[session].ended = true;
  ++ended_;  // S changed: every other dynamic part is stale
  sessions_[session].part_version = ended_;
  return stats;
}

TsdfMap ChangeDetector::staticMap() { return backend_->staticMap(); }

TsdfMap ChangeDetector::sessionMap(int session) {
  requireLayers(session, "sessionMap");
  return backend_->sessionMap(session);
}

LabelMap ChangeDetector::labels() { return backend_->labels(); }

LabelMap ChangeDetector::sessionDynamic(int session) {
  requireLayers(session, "sessionDynamic");
  if (!sessions_[session].ended) {
    throw InputError("sessionDynamic: session " + std::to_string(session) +
                     " has not ended (its dynamic part is computed by endSession)");
  }
  if (sessions_[session].part_version != ended_) {
    backend_->refreshDynamic(session);
    sessions_[session].part_version = ended_;
  }
  return backend_->sessionDynamic(session);
}

DeviceTsdfMap* ChangeDetector::deviceMap() { return backend_->deviceMap(); }
DeviceFusion* ChangeDetector::deviceFusion() { return backend_->deviceFusion(); }

}  // namespace strata::change
