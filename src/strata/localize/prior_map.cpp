// The prior map: a store's keyframes with map-frame poses, images and descriptors, indexed.
#include "strata/localize/prior_map.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "strata/align/store_alignment.h"
#include "strata/core/error.h"
#include "strata/core/parallel_for.h"

namespace strata::localize {
namespace {

/// A keyframe to load: where its images are and what is known of it already.
struct LoadJob {
  const Dataset* frames = nullptr;
  std::size_t frame = 0;
  MapKeyframe keyframe;  // pose, ids, timestamp filled
  std::optional<store::FeatureSet> stored;
};

}  // namespace

void PriorMapConfig::validate() const {
  features.validate();
  index.validate();
  surface.validate();
  if (threads < 1) throw InputError("prior map: threads must be >= 1");
}

PriorMap::PriorMap(std::vector<MapKeyframe> keyframes, const PriorMapConfig& config)
    : config_(config), keyframes_(std::move(keyframes)), index_(config.index) {
  config_.validate();
  if (keyframes_.empty()) throw InputError("prior map: no keyframe");
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    if (!keyframes_[k].T_W_C.matrix().allFinite())
      throw InputError("prior map: keyframe " + std::to_string(k) + " has a non-finite pose");
    if (keyframes_[k].features.size() > 0) index_.add(k, keyframes_[k].features);
  }
}

MapKeyframe describeKeyframe(RgbdFrame frame, const CameraIntrinsics& intrinsics,
                             const PriorMapConfig& config) {
  MapKeyframe k;
  k.timestamp_s = frame.timestamp_s;
  k.T_W_C = frame.T_W_C;
  k.intrinsics = intrinsics;
  if (!frame.color.empty())
    k.features = align::extractFeatures(frame.color, frame.depth, intrinsics, config.features);
  if (config.surfaces) k.surface = align::describeSurface(frame.depth, intrinsics, config.surface);
  k.depth = std::move(frame.depth);
  return k;
}

PriorMap PriorMap::fromStore(store::Store& store, const PriorMapConfig& config,
                             const PriorMapProgress& progress) {
  config.validate();
  const std::vector<store::SessionRecord> sessions = store.sessions();
  if (sessions.empty()) throw InputError("map database '" + store.path() + "' has no session");
  const bool any_aligned = std::any_of(sessions.begin(), sessions.end(),
                                       [](const store::SessionRecord& s) { return s.aligned; });
  std::vector<std::unique_ptr<Dataset>> datasets;
  std::vector<LoadJob> jobs;
  std::vector<std::string> used, skipped;
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    const store::SessionRecord& record = sessions[s];
    // Nothing aligned: the first session anchors the map frame (what alignment would make it).
    const bool usable = any_aligned ? (record.aligned && record.T_W_S.has_value()) : s == 0;
    if (!usable) {
      skipped.push_back(record.name);
      continue;
    }
    const Eigen::Isometry3d T_W_S = any_aligned ? *record.T_W_S : Eigen::Isometry3d::Identity();
    datasets.push_back(align::openStoredSession(store, record));
    const Dataset& frames = *datasets.back();
    std::vector<double> times;
    for (std::size_t i = 0; i < frames.size(); ++i) times.push_back(frames.stamp(i).timestamp_s);
    std::size_t last_frame = frames.size();
    for (const store::KeyframeRecord& k : store.keyframes(record.id)) {
      const std::size_t frame = align::keyframeFrame(times, k.timestamp_s, record);
      if (frame == last_frame) continue;
      last_frame = frame;
      LoadJob job;
      job.frames = &frames;
      job.frame = frame;
      job.keyframe.store_id = k.id;
      job.keyframe.session_id = record.id;
      job.keyframe.session_name = record.name;
      job.keyframe.timestamp_s = k.timestamp_s;
      job.keyframe.T_W_C = k.T_W_C.value_or(T_W_S * k.T_S_C);
      job.stored = store.features(k.id);
      jobs.push_back(std::move(job));
    }
    used.push_back(record.name);
  }
  if (jobs.empty()) throw InputError("map database '" + store.path() + "' has no keyframe");

  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  parallelForEach(jobs.size(), config.threads, [&](std::size_t j) {
    LoadJob& job = jobs[j];
    MapKeyframe& k = job.keyframe;
    RgbdFrame frame = job.frames->load(job.frame);
    const CameraIntrinsics intrinsics = job.frames->intrinsics();
    if (job.stored) frame.color = ColorImage();  // the stored features are lifted instead
    MapKeyframe described = describeKeyframe(std::move(frame), intrinsics, config);
    k.intrinsics = intrinsics;
    k.depth = std::move(described.depth);
    k.features = job.stored ? align::liftFeatures(*job.stored, k.depth, intrinsics, config.features)
                            : std::move(described.features);
    k.surface = std::move(described.surface);
    const std::size_t finished = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(finished, jobs.size());
    }
  });
  std::vector<MapKeyframe> keyframes;
  keyframes.reserve(jobs.size());
  for (LoadJob& job : jobs) keyframes.push_back(std::move(job.keyframe));
  PriorMap map(std::move(keyframes), config);
  map.sessions_ = std::move(used);
  map.skipped_sessions_ = std::move(skipped);
  return map;
}

}  // namespace strata::localize
