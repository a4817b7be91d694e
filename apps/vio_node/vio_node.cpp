// VioNode, receive side: subscriptions and the handlers of the stereo and IMU channels.
#include "vio_node/vio_node.h"

#include <cstdio>
#include <exception>
#include <limits>
#include <thread>

#include "strata/core/error.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/receive_loop.h"

namespace strata::apps {
namespace {

constexpr int kReceiveTimeoutMs = 50;
/// IMU samples queued at most: 10 s at 200 Hz (only a stalled worker gets there).
constexpr std::size_t kMaxQueuedImu = 2000;
/// utimes whose nanoseconds fit int64 (the pipeline's clock): up to the year 2262.
constexpr std::int64_t kMaxUtime = std::numeric_limits<std::int64_t>::max() / 1000;

void checkUtime(std::int64_t utime, const char* what) {
  if (utime < 0 || utime > kMaxUtime) {
    throw InputError(std::string(what) + " utime " + std::to_string(utime) + " is outside 0.." +
                     std::to_string(kMaxUtime));
  }
}

/// The child frame of the published poses.
std::string leftCameraName(const euroc::Calibration& calibration) {
  if (calibration.cameras.empty() || calibration.cameras[0].name.empty()) return "cam0";
  return calibration.cameras[0].name;
}

}  // namespace

VioNode::VioNode(lcm::LCM& input, lcm::LCM& output, const euroc::Calibration& calibration,
                 const VioOptions& options)
    : input_(input),
      output_(output),
      options_(options),
      left_camera_(leftCameraName(calibration)),
      input_stats_("strata-vio"),
      queue_(options.queue_frames, kMaxQueuedImu),
      started_(Clock::now()),
      last_input_(Clock::now().time_since_epoch().count()),
      core_(calibration, options.pipeline),
      next_report_(started_ + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(options.status_period_s))),
      last_report_(started_) {
  if (!input_.good()) throw InputError("LCM input '" + options.url + "' could not be opened");
  if (!output_.good()) throw InputError("LCM output could not be opened");
  subscriptions_.push_back(input_.subscribe(options_.channels.stereo, &VioNode::onStereo, this));
  subscriptions_.push_back(input_.subscribe(options_.channels.imu, &VioNode::onImu, this));
}

VioNode::~VioNode() {
  for (lcm::Subscription* s : subscriptions_) input_.unsubscribe(s);
}

void VioNode::receiveLoop() {
  // NOTE: the input stops e.g. at the end of a log file (file:// provider): keep processing what is
  // queued.
  lcm_io::receiveUntilStopped(input_, receiving_, kReceiveTimeoutMs, [] {
    std::fprintf(stderr, "strata-vio: LCM input stopped delivering messages\n");
  });
}

void VioNode::onStereo(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  last_input_ = Clock::now().time_since_epoch().count();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_received;
  }
  try {
    stereo_image_t message;
    lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
    checkUtime(message.utime, "stereo frame");
    enqueue(lcm_io::decodeStereo(message));
  } catch (const std::exception& e) {  // InputError, or bad_alloc from a huge valid message
    input_stats_.countBad(channel, e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_corrupt;
  }
}

void VioNode::onImu(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  last_input_ = Clock::now().time_since_epoch().count();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.imu_received;
  }
  imu_t message;
  try {
    lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
    checkUtime(message.utime, "IMU sample");
  } catch (const std::exception& e) {
    input_stats_.countBad(channel, e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.imu_corrupt;
    return;
  }
  try {
    enqueue(lcm_io::decodeImu(message));  // refuses only non-finite values
  } catch (const InputError& e) {
    input_stats_.countBad(channel, e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.imu_nonfinite;
  }
}

void VioNode::enqueue(SensorQueue::Item item) {
  const SensorQueue::Dropped dropped = queue_.push(std::move(item));
  if (dropped.frames == 0 && dropped.imu == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  counters_.frames_dropped_backlog += static_cast<std::int64_t>(dropped.frames);
  counters_.imu_dropped_backlog += static_cast<std::int64_t>(dropped.imu);
}

bool VioNode::idle() const {
  if (options_.max_idle_s <= 0.0) return false;
  const Clock::time_point last{Clock::duration(last_input_.load())};
  return std::chrono::duration<double>(Clock::now() - last).count() > options_.max_idle_s;
}

VioCounters VioNode::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

}  // namespace strata::apps
