#include "player/play_run.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "io/euroc_dataset.h"
#include "player/play_euroc.h"
#include "player/play_flow.h"
#include "player/play_publisher.h"
#include "player/play_source.h"
#include "cli/progress.h"
#include "core/error.h"
#include "lcm/lcm_time.h"

namespace strata::apps {
namespace {

using Clock = std::chrono::steady_clock;

/// How long flow control waits for the mapper to account for a frame before taking it as lost
/// in transit (UDP) and sending on.
constexpr double kLostFrameWaitS = 1.0;

class Player {
 public:
  Player(const PlayOptions& options, lcm::LCM& lcm)
      : o_(options),
        source_(
            openPlaySource(options.dataset, options.sim_frames, options.sim_noise, options.imu)),
        publisher_(lcm, channels(options), options.camera_id, encoding(options)),
        watcher_(lcm, options.stats_channel) {
    source_.dataset->intrinsics().validate();
    for (std::size_t i = static_cast<std::size_t>(o_.first); i < source_.dataset->size();
         i += o_.stride) {
      if (o_.frames > 0 && indices_.size() >= static_cast<std::size_t>(o_.frames)) break;
      indices_.push_back(i);
    }
    if (indices_.empty()) throw InputError("'" + o_.dataset + "' has no frames to send");
  }

  void play() {
    if (o_.rate == 0.0 &&
        !watcher_.waitFor([&] { return watcher_.heard(); }, o_.mapper_timeout_s)) {
      throw InputError("no map_stats_t from a mapper on " + o_.stats_channel + " within " +
                       std::to_string(o_.mapper_timeout_s) + " s (is strata-mapper running on " +
                       o_.url + "?)");
    }
    ProgressBar progress("sending", indices_.size(), !o_.quiet);
    const auto start = Clock::now();
    const double t0_s = source_.dataset->load(indices_.front()).timestamp_s;
    const std::int64_t base_utime = lcm_io::nowUtime();
    std::size_t imu_next = 0;
    for (std::size_t n = 0; n < indices_.size(); ++n) {
      const RgbdFrame frame = source_.dataset->load(indices_[n]);
      const double offset_s = frame.timestamp_s - t0_s;
      if (o_.rate > 0.0)
        waitUntil(start + std::chrono::duration_cast<Clock::duration>(
                              std::chrono::duration<double>(offset_s / o_.rate)));
      else
        waitForWindow(n);
      const std::int64_t utime = o_.restamp ? base_utime + lcm_io::secondsToUtime(offset_s)
                                            : lcm_io::secondsToUtime(frame.timestamp_s);
      imu_next = sendImuUntil(frame.timestamp_s, t0_s, base_utime, imu_next);
      bytes_ += publisher_.publish(frame, source_.dataset->intrinsics(), utime);
      progress.update(n + 1);
    }
    progress.finish();
    seconds_ = std::chrono::duration<double>(Clock::now() - start).count();
  }

  /// STOP_SESSION and SAVE_MAP as asked; false when the mapper did not confirm.
  bool finish() {
    bool ok = true;
    if (o_.end_session) ok = sendAndWait(command_t::STOP_SESSION, "") && ok;
    if (!o_.save_path.empty()) ok = sendAndWait(command_t::SAVE_MAP, o_.save_path) && ok;
    watcher_.pump(200);
    return ok;
  }

  void printSummary() const {
    const double n = static_cast<double>(indices_.size());
    std::printf("strata-play: sent %zu frames of '%s' (%.1f MB) in %.2f s, %.1f frames/s%s.",
                indices_.size(), source_.dataset->name().c_str(), bytes_ / 1e6, seconds_,
                seconds_ > 0 ? n / seconds_ : 0.0, lost_ ? " (some taken as lost in transit)" : "");
    if (watcher_.heard()) {
      const map_stats_t& s = watcher_.latest();
      std::printf(
          " Mapper: %lld fused, %lld dropped behind its queue, %lld without pose, %lld "
          "rejected, %lld bad messages, %lld blocks, %.1f ms per frame.",
          (long long)s.frames_fused, (long long)s.frames_dropped_backlog,
          (long long)s.frames_dropped_no_pose, (long long)s.frames_rejected,
          (long long)s.messages_bad, (long long)s.blocks, s.fuse_ms_mean);
    } else {
      std::printf(" No mapper heard on %s.", o_.stats_channel.c_str());
    }
    std::printf("\n");
  }

 private:
  static PublisherChannels channels(const PlayOptions& o) {
    return {o.rgbd_channel, o.camera_info_channel, o.pose_channel, o.imu_channel,
            o.command_channel};
  }
  static lcm_io::FrameEncoding encoding(const PlayOptions& o) {
    lcm_io::FrameEncoding e = o.encoding;
    e.with_pose = !o.separate_poses;
    return e;
  }

  void waitUntil(Clock::time_point when) {
    while (Clock::now() < when) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(when - Clock::now());
      watcher_.pump(
          static_cast<int>(std::max<long long>(0, std::min<long long>(left.count(), 20))));
    }
  }

  /// Flow control: at most `window` frames the mapper has not accounted for.
  void waitForWindow(std::size_t sent) {
    const auto in_flight = [&] {
      return static_cast<std::int64_t>(sent) - lost_ - watcher_.framesAccounted();
    };
    const auto started = Clock::now();
    while (!watcher_.waitFor([&] { return in_flight() < o_.window; }, kLostFrameWaitS)) {
      const double waited_s = std::chrono::duration<double>(Clock::now() - started).count();
      if (waited_s > o_.mapper_timeout_s) {
        throw InputError("the mapper accounted for no frame in " +
                         std::to_string(o_.mapper_timeout_s) + " s (stopped?)");
      }
      // Nothing queued on the mapper's side: the missing frames never arrived (UDP loss).
      if (watcher_.latest().queue_depth == 0) lost_ += in_flight() - o_.window + 1;
    }
  }

  std::size_t sendImuUntil(double t_s, double t0_s, std::int64_t base_utime, std::size_t next) {
    for (; next < source_.imu.size() && source_.imu[next].t_s <= t_s; ++next) {
      const double offset_s = source_.imu[next].t_s - t0_s;
      if (offset_s < 0.0) continue;
      publisher_.publishImu(source_.imu[next], base_utime + lcm_io::secondsToUtime(offset_s));
    }
    return next;
  }

  bool sendAndWait(std::int8_t command, const std::string& argument) {
    const std::int64_t id = publisher_.command(command, argument);
    std::string result;
    if (!watcher_.waitFor([&] { return watcher_.commandDone(id, &result); }, o_.mapper_timeout_s)) {
      std::fprintf(stderr, "strata-play: the mapper did not confirm command %d within %.0f s\n",
                   command, o_.mapper_timeout_s);
      return false;
    }
    if (result != "ok") std::fprintf(stderr, "strata-play: mapper: %s\n", result.c_str());
    return result == "ok";
  }

  PlayOptions o_;
  PlaySource source_;
  FramePublisher publisher_;
  MapperWatcher watcher_;
  std::vector<std::size_t> indices_;
  std::size_t bytes_ = 0;
  std::int64_t lost_ = 0;
  double seconds_ = 0.0;
};

}  // namespace

int runPlay(const PlayOptions& options) {
  try {
    options.validate();
    lcm::LCM lcm(options.url);
    if (!lcm.good()) throw InputError("LCM URL '" + options.url + "' could not be opened");
    // NOTE: `strata sim --stereo` sessions hold both layouts: the folder plays as TUM RGB-D (for
    // the mapper), its mav0/ as grey stereo + IMU.
    if (euroc::isEurocFolder(options.dataset) &&
        !std::filesystem::exists(std::filesystem::path(options.dataset) / "depth.txt")) {
      const EurocPlaySummary s = playEuroc(options, lcm);
      std::printf("strata-play: sent %zu grey frames on %s and %zu IMU samples on %s of '%s' "
                  "(%.1f MB) in %.2f s.\n",
                  s.frames, options.stereo_channel.c_str(), s.imu_samples,
                  options.imu_channel.c_str(), options.dataset.c_str(), s.bytes / 1e6, s.seconds);
      return 0;
    }
    Player player(options, lcm);
    player.play();
    const bool confirmed = player.finish();
    player.printSummary();
    return confirmed ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-play: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-play: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
