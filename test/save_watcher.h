#pragma once
// Watches one file's atomic saves from outside the writing process (inotify on its folder): the
// creation of its temporary `<name>.tmp.<pid>` (the write began) and the rename onto `<name>`
// (the write ended). The kill tests classify where a SIGKILL landed by these events: the kernel
// queues them as the writer acts, so after waitpid() the record is complete.
// Thread safety: not thread safe.
#include <chrono>
#include <filesystem>
#include <optional>

namespace strata::test {

enum class KillLanding { kBefore, kDuring, kAfter };
const char* landingName(KillLanding landing);

class SaveWatcher {
 public:
  using Clock = std::chrono::steady_clock;

  /// Throws std::runtime_error when inotify cannot watch the folder of `target`.
  explicit SaveWatcher(const std::filesystem::path& target);
  ~SaveWatcher();
  SaveWatcher(const SaveWatcher&) = delete;
  SaveWatcher& operator=(const SaveWatcher&) = delete;

  /// Forgets what was seen (and drains what is queued), before the next process starts.
  void reset();
  /// Reads events for up to `timeout_s` (0: only those queued).
  void poll(double timeout_s);
  /// Keeps reading events for `seconds` (so that their times stay exact).
  void watchFor(double seconds);
  /// Polls until the temporary was created / the rename landed, or `timeout_s` passes.
  bool waitForTemporary(double timeout_s);
  bool waitForRename(double timeout_s);

  /// When each was first seen since reset() (to the poll's granularity), if it was.
  std::optional<Clock::time_point> temporaryCreated() const { return created_; }
  std::optional<Clock::time_point> renamed() const { return renamed_; }
  /// Before (no temporary), during (temporary, no rename), after (renamed).
  KillLanding landing() const;
  /// Files `<name>.tmp.*` in the folder now.
  int temporariesPresent() const;

 private:
  template <typename Seen>
  bool waitFor(Seen seen, double timeout_s);

  std::filesystem::path target_;
  int fd_ = -1;
  std::optional<Clock::time_point> created_, renamed_;
};

}  // namespace strata::test
