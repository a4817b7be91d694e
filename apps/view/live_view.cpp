// LiveView: subscriptions, the dispatch loop, meshes, the ESDF slice, stats and requests.
#include "view/live_view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "strata/core/error.h"
#include "strata/lcm/lcm_time.h"
#include "view/live_decode.h"
#include "view/live_items.h"

namespace strata::view {
namespace {

double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Message errorMessage(const std::string& text) {
  return encodeMessage({{"type", "error"}, {"message", text}});
}

std::string metres(float value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f m", value);
  return text;
}

}  // namespace

LiveView::LiveView(lcm::LCM& lcm, Scene& scene, LiveChannels channels, const std::string& title,
                   ErrorLog log)
    : lcm_(lcm), scene_(scene), channels_(std::move(channels)), log_(std::move(log)) {
  if (!lcm_.good()) throw InputError("strata-view: the LCM object could not be opened");
  const LiveChannels& c = channels_;
  subscriptions_ = {lcm_.subscribe(c.mesh, &LiveView::onMesh, this),
                    lcm_.subscribe(c.esdf, &LiveView::onEsdf, this),
                    lcm_.subscribe(c.stats, &LiveView::onStats, this),
                    lcm_.subscribe(c.change, &LiveView::onChange, this),
                    lcm_.subscribe(c.objects, &LiveView::onObjects, this),
                    lcm_.subscribe(c.pose, &LiveView::onPose, this),
                    lcm_.subscribe(c.rgbd, &LiveView::onFrame, this),
                    lcm_.subscribe(c.camera_info, &LiveView::onCameraInfo, this)};
  scene_.put("hello", encodeMessage(
                          {{"type", "hello"}, {"title", title}, {"mode", "live"}, {"esdf", true}}));
  stats_dirty_ = true;
  flush();
}

LiveView::~LiveView() {
  for (lcm::Subscription* s : subscriptions_) {
    if (s != nullptr) lcm_.unsubscribe(s);
  }
}

int LiveView::handle(int timeout_ms) {
  const int handled = lcm_.handleTimeout(timeout_ms);
  if (nowSeconds() - last_flush_s_ >= kFlushPeriod_s) flush();
  return handled;
}

void LiveView::flush() {
  last_flush_s_ = nowSeconds();
  for (auto [trajectory, id] :
       {std::pair{&map_trajectory_, "map"}, std::pair{&vio_trajectory_, "vio"}}) {
    if (!trajectory->dirty) continue;
    trajectory->dirty = false;
    scene_.put(std::string("trajectory:") + id,
               polylineMessage("trajectory", id, trajectory->points_W));
  }
  if (stats_dirty_) putStats();
}

template <typename Apply>
void LiveView::guarded(const std::string& channel, Apply apply) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.messages;
  }
  try {
    apply();
    return;
  } catch (const std::exception& e) {
    std::uint64_t bad = 0;
    const std::string line = channel + ": " + e.what();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      bad = ++counters_.bad_messages;
      counters_.last_error = line;
    }
    stats_dirty_ = true;
    if (log_ && (bad <= 10 || bad % 100 == 0)) {
      log_("bad message " + std::to_string(bad) + " skipped: " + line);
    }
  }
}

void LiveView::onMesh(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    const mesh_update_t update =
        decodeMeshUpdate(buffer->data, static_cast<int>(buffer->data_size));
    // Every block converted before any is shown: a bad block leaves the scene as it was.
    std::vector<std::pair<std::string, Message>> items;
    items.reserve(update.blocks.size());
    for (const mesh_block_t& block : update.blocks) {
      const std::string id = blockId(block.index);
      const Mesh mesh = blockMesh(block);
      items.emplace_back(id, mesh.triangles.empty()
                                 ? nullptr
                                 : meshMessage(id, "map", mesh, -1, "", update.utime));
    }
    std::uint64_t lost = 0;
    if (last_sequence_ && !update.full && update.sequence > *last_sequence_ + 1) {
      lost = static_cast<std::uint64_t>(update.sequence - *last_sequence_ - 1);
    }
    last_sequence_ = update.sequence;
    if (update.full) {
      std::set<std::string> kept;
      for (const auto& [id, message] : items) {
        if (message) kept.insert(id);
      }
      for (const std::string& id : blocks_) {
        if (kept.count(id) == 0) scene_.remove(id);
      }
      blocks_.clear();
    }
    for (auto& [id, message] : items) {
      if (message) {
        scene_.put(id, std::move(message));
        blocks_.insert(id);
      } else {
        scene_.remove(id);
        blocks_.erase(id);
      }
    }
    const double latency_ms = static_cast<double>(lcm_io::nowUtime() - update.utime) * 1e-3;
    std::lock_guard<std::mutex> lock(mutex_);
    counters_.mesh_latency_ms_last = latency_ms;
    counters_.mesh_latency_ms_max = std::max(counters_.mesh_latency_ms_max, latency_ms);
    ++counters_.mesh_updates;
    counters_.mesh_updates_lost += lost;
    counters_.blocks = blocks_.size();
    stats_dirty_ = true;
  });
}

void LiveView::onEsdf(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    const esdf_slice_t message = decodeEsdfSlice(buffer->data, static_cast<int>(buffer->data_size));
    EsdfSliceImage image = sliceImage(message);
    if (image.width == 0 || image.height == 0) {
      // No block holds the slice's height (yet): nothing to draw or to read distances from.
      {
        std::lock_guard<std::mutex> lock(mutex_);
        slice_.reset();
      }
      scene_.remove("esdf");
      return;
    }
    Message drawn = esdfSliceMessage(image);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      slice_ = std::move(image);
    }
    scene_.put("esdf", std::move(drawn));
  });
}

void LiveView::onStats(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(channel, [&] {
    mapper_stats_ = statsValues(decodeMapStats(buffer->data, static_cast<int>(buffer->data_size)));
    putStats();
  });
}

void LiveView::putStats() {
  stats_dirty_ = false;
  nlohmann::json values = mapper_stats_;
  const LiveCounters c = counters();
  values["mesh blocks"] = c.blocks;
  values["view bad messages"] = c.bad_messages;
  if (c.mesh_updates_lost > 0) values["mesh updates lost"] = c.mesh_updates_lost;
  if (c.mesh_updates > 0) values["view mesh ms"] = c.mesh_latency_ms_last;
  scene_.put("stats", encodeMessage({{"type", "stats"}, {"values", std::move(values)}}));
}

Message LiveView::answer(const nlohmann::json& request) {
  if (!request.is_object()) throw InputError("a request must be a JSON object");
  const std::string type = request.value("type", "");
  std::optional<EsdfSliceImage> slice;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    slice = slice_;  // NOTE: a copy, so no lock is held while answering
  }
  if (type == "slice") {
    return errorMessage("the mapper chooses the live slice's height (strata-mapper --slice-z)" +
                        (slice ? "; this one is at z = " + metres(slice->z_m) : std::string()));
  }
  if (type != "query") throw InputError("unknown request type '" + type + "'");
  const auto p = request.value("point", nlohmann::json());
  if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
    throw InputError("query: point must be [x, y, z] in metres");
  const Eigen::Vector3f point(p[0].get<float>(), p[1].get<float>(), p[2].get<float>());
  if (!point.allFinite()) throw InputError("query: point must be finite");
  if (!slice) {
    return errorMessage("no ESDF slice received yet on " + channels_.esdf +
                        " (strata-mapper publishes one when --esdf-rate > 0 and the map reaches "
                        "its height)");
  }
  if (std::abs(point.z() - slice->z_m) > 0.5f * slice->resolution_m) {
    return errorMessage("the live view only knows the ESDF slice at z = " + metres(slice->z_m) +
                        " (within " + metres(0.5f * slice->resolution_m) +
                        "); the point is at z = " + metres(point.z()));
  }
  const std::optional<float> d = sliceDistance(*slice, point.x(), point.y());
  return answerMessage(request.value("id", 0), point, d.has_value(), d.value_or(0.0f));
}

LiveCounters LiveView::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

}  // namespace strata::view
