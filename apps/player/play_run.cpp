#include "player/play_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "strata/core/progress.h"
#include "strata/core/error.h"
#include "strata/io/euroc_dataset.h"
#include "strata/lcm/lcm_time.h"
#include "player/play_euroc.h"
#include "player/play_flow.h"
#include "player/play_publisher.h"
#include "player/play_source.h"
#include "player/play_with_stereo.h"

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
    if (o_.with_stereo) grey_ = std::make_unique<GreyInterleave>(o_, lcm);
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
    start_ = Clock::now();
    t0_s_ = source_.dataset->load(indices_.front()).timestamp_s;
    base_utime_ = lcm_io::nowUtime();
    const GreyInterleave::Pace pace = [this](std::int64_t t_ns) { return paceGrey(t_ns); };
    if (grey_) grey_->skipBefore(toNs(t0_s_));
    for (std::size_t n = 0; n < indices_.size(); ++n) {
      const RgbdFrame frame = source_.dataset->load(indices_[n]);
      if (grey_) {
        const std::int64_t t_ns = toNs(frame.timestamp_s);
        if (grey_->pastEnd(t_ns)) {  // and so are the frames after it
          outside_grey_ += indices_.size() - n;
          break;
        }
        if (!grey_->covers(t_ns)) {
          ++outside_grey_;
          continue;
        }
        grey_->sendThrough(t_ns, pace);
      }
      sendFrame(frame, n);
      progress.update(n + 1);
    }
    if (grey_) grey_->finish(pace);
    progress.finish();
    seconds_ = std::chrono::duration<double>(Clock::now() - start_).count();
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
    const std::size_t sent = indices_.size() - outside_grey_;
    std::printf("strata-play: sent %zu frames of '%s' (%.1f MB) in %.2f s, %.1f frames/s%s.", sent,
                source_.dataset->name().c_str(), bytes_ / 1e6, seconds_,
                seconds_ > 0 ? static_cast<double>(sent) / seconds_ : 0.0,
                lost_ ? " (some taken as lost in transit)" : "");
    if (grey_) {
      const EurocPlaySummary& g = grey_->sent();
      std::printf(
          " With them %zu grey frames on %s and %zu IMU samples on %s (%.1f MB); %zu RGB-D "
          "frames outside the grey recording not sent.",
          g.frames, o_.stereo_channel.c_str(), g.imu_samples, o_.imu_channel.c_str(), g.bytes / 1e6,
          outside_grey_);
    }
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
    // NOTE: no pose channel: with --no-poses nothing is sent there (a VIO provides the poses).
    return {o.rgbd_channel, o.camera_info_channel, o.poses ? o.pose_channel : "", o.imu_channel,
            o.command_channel};
  }
  static lcm_io::FrameEncoding encoding(const PlayOptions& o) {
    lcm_io::FrameEncoding e = o.encoding;
    e.with_pose = o.poses && !o.separate_poses;
    return e;
  }
  static std::int64_t toNs(double t_s) { return std::llround(t_s * 1e9); }

  /// Frame `n` of the picked ones, paced (rate) or flow-controlled, after the IMU before it.
  void sendFrame(const RgbdFrame& frame, std::size_t n) {
    const double offset_s = frame.timestamp_s - t0_s_;
    if (o_.rate > 0.0)
      waitUntil(at(offset_s));
    else
      waitForWindow(n);
    const std::int64_t utime = o_.restamp ? base_utime_ + lcm_io::secondsToUtime(offset_s)
                                          : lcm_io::secondsToUtime(frame.timestamp_s);
    imu_next_ = sendImuUntil(frame.timestamp_s, t0_s_, base_utime_, imu_next_);
    bytes_ += publisher_.publish(frame, source_.dataset->intrinsics(), utime);
  }

  /// --with-stereo: a grey event at recording time `t_ns` waits for its moment and is stamped
  /// on the RGB-D frames' clock (offsets from the first frame).
  std::int64_t paceGrey(std::int64_t t_ns) {
    const std::int64_t offset_ns = t_ns - toNs(t0_s_);
    waitUntil(at(1e-9 * static_cast<double>(offset_ns)));
    return o_.restamp ? base_utime_ + offset_ns / 1000 : t_ns / 1000;
  }

  /// When the event `offset_s` into the recording is due at --rate.
  Clock::time_point at(double offset_s) const {
    return start_ + std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>(offset_s / o_.rate));
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
  std::unique_ptr<GreyInterleave> grey_;  // --with-stereo
  std::vector<std::size_t> indices_;
  std::size_t outside_grey_ = 0;  // RGB-D frames outside the grey recording, not sent
  Clock::time_point start_;       // of the replay
  double t0_s_ = 0.0;             // recording time of the first frame
  std::int64_t base_utime_ = 0;   // its stamp when restamping
  std::size_t imu_next_ = 0;      // next synthetic IMU sample to send
  std::size_t bytes_ = 0;
  std::int64_t lost_ = 0;
  double seconds_ = 0.0;
};

/// The replay on `lcm`: EuRoC folders as grey stereo + IMU, everything else as RGB-D frames.
int play(const PlayOptions& options, lcm::LCM& lcm) {
  // NOTE: `strata sim --stereo` sessions hold both layouts: the folder plays as TUM RGB-D (for
  // the mapper), its mav0/ as grey stereo + IMU (alone, or with --with-stereo beside the frames).
  if (euroc::isEurocFolder(options.dataset) &&
      !std::filesystem::exists(std::filesystem::path(options.dataset) / "depth.txt")) {
    if (options.with_stereo) {
      throw InputError("--with-stereo: '" + options.dataset +
                       "' has no TUM RGB-D frames to send the grey stream with (it plays as "
                       "grey stereo + IMU without the flag)");
    }
    const EurocPlaySummary s = playEuroc(options, lcm);
    std::printf(
        "strata-play: sent %zu grey frames on %s and %zu IMU samples on %s of '%s' "
        "(%.1f MB) in %.2f s.\n",
        s.frames, options.stereo_channel.c_str(), s.imu_samples, options.imu_channel.c_str(),
        options.dataset.c_str(), s.bytes / 1e6, s.seconds);
    return 0;
  }
  if (options.with_stereo) mav0Folder(options);  // before the frames are read
  Player player(options, lcm);
  player.play();
  const bool confirmed = player.finish();
  player.printSummary();
  return confirmed ? 0 : 1;
}

/// `run`'s exit code, or the code of the error it threw, with a message naming the problem.
template <typename Run>
int exitCode(Run run) {
  try {
    return run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-play: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-play: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int runPlay(const PlayOptions& options) {
  return exitCode([&] {
    options.validate();
    lcm::LCM lcm(options.url);
    if (!lcm.good()) throw InputError("LCM URL '" + options.url + "' could not be opened");
    return play(options, lcm);
  });
}

int runPlay(const PlayOptions& options, lcm::LCM& lcm) {
  return exitCode([&] {
    options.validate();
    return play(options, lcm);
  });
}

}  // namespace strata::apps
